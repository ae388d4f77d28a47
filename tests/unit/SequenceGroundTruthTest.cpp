#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "boneless/Sampling.h"
#include "boneless/SequenceEvaluation.h"

using namespace boneless;
namespace fs = std::filesystem;

namespace {

// Unpacks a ground-truth archive from ../shared/data into the build tree once; empty when the
// shared data is absent (the test then skips).
std::string unpacked(const std::string& archive, const std::string& folder) {
    const fs::path source = fs::path(BONELESS_SHARED_DATA) / "sequences" / archive;
    if (!fs::exists(source)) return {};
    const fs::path target = fs::path(BONELESS_TEST_WORK_DIR) / "sequences";
    const fs::path frames = target / folder;
    if (!fs::exists(frames)) {
        fs::create_directories(target);
        const std::string command =
            "tar -xJf '" + source.string() + "' -C '" + target.string() + "'";
        if (std::system(command.c_str()) != 0) return {};
    }
    return frames.string();
}

struct Bound {
    double rmsMean, rmsWorst;
    int flippedMax;
};

// Measured with the default evaluation options (the direct method, the orientation guard on),
// K = 40, every frame: horse 1.031 % mean, 1.441 % worst frame, 222 flipped faces at most; samba
// 1.070 %, 1.680 %, 455. The bounds add about 4 % (5 % on flips) for floating-point differences
// between machines.
constexpr Bound kHorseMeasured{1.031, 1.441, 222};
constexpr Bound kHorseBound{1.07, 1.50, 233};
constexpr Bound kSambaBound{1.11, 1.75, 478};

Evaluation evaluateAtFortyMarkers(const MeshSequence& sequence,
                                  SolverOptions::Method method = SolverOptions::Method::Direct) {
    EvaluationOptions options;
    options.markers = geodesicFarthestPoints(sequence.rest, 40, 0);
    options.solver.method = method;
    return evaluateSequence(sequence, options);
}

void expectWithin(const std::string& folder, const Bound& boneless, const Bound& arapReference) {
    const MeshSequence sequence = readMeshSequence(folder);
    const Evaluation e = evaluateAtFortyMarkers(sequence);
    const auto& s = e.summary;
    EXPECT_EQ(s.frames, static_cast<int>(sequence.frames.size()) - 1);
    EXPECT_LE(s.rmsPctMean, boneless.rmsMean);
    EXPECT_LE(s.rmsPctWorstFrame, boneless.rmsWorst);
    EXPECT_LE(s.flippedFacesMax, boneless.flippedMax);
    EXPECT_EQ(s.foldedFacesMax, 0);  // turned away from the truth, perhaps, but never folded
    // The reference: libigl's ARAP with the same markers. Boneless must not be worse.
    EXPECT_LE(s.rmsPctMean, arapReference.rmsMean);
    EXPECT_LE(s.rmsPctWorstFrame, arapReference.rmsWorst);
    EXPECT_LE(s.flippedFacesMax, arapReference.flippedMax);
    for (const auto& f : e.frames) EXPECT_TRUE(std::isfinite(f.rmsPct)) << "frame " << f.frame;
}

}  // namespace

TEST(SequenceGroundTruth, HorseGallopAtFortyMarkers) {
    const std::string folder = unpacked("horse-gallop/horse-gallop.tar.xz", "horse-gallop");
    if (folder.empty()) GTEST_SKIP() << "no shared data (" << BONELESS_SHARED_DATA << ")";
    expectWithin(folder, kHorseBound, {1.218, 1.718, 305});
}

TEST(SequenceGroundTruth, SambaAtFortyMarkers) {
    const std::string folder = unpacked("samba/samba.tar.xz", "samba");
    if (folder.empty()) GTEST_SKIP() << "no shared data (" << BONELESS_SHARED_DATA << ")";
    expectWithin(folder, kSambaBound, {1.324, 2.016, 554});
}

// Issue 4: the multiresolution method is a faster way to the same answer, so its figures stay
// within 5 % of the direct method's (kHorseMeasured), and like it, it folds no face. Measured:
// 1.022 %, 1.458 %, 198 faces, none folded (5 with the input level's one step a frame and no
// more for a face turned over), at a fifth of the time per frame.
TEST(SequenceGroundTruth, TheMultiresolutionMethodKeepsTheHorsesAccuracy) {
    const std::string folder = unpacked("horse-gallop/horse-gallop.tar.xz", "horse-gallop");
    if (folder.empty()) GTEST_SKIP() << "no shared data (" << BONELESS_SHARED_DATA << ")";
    const auto s =
        evaluateAtFortyMarkers(readMeshSequence(folder), SolverOptions::Method::Multiresolution)
            .summary;
    EXPECT_LE(s.rmsPctMean, 1.05 * kHorseMeasured.rmsMean);
    EXPECT_LE(s.rmsPctWorstFrame, 1.05 * kHorseMeasured.rmsWorst);
    EXPECT_LE(s.flippedFacesMax, 1.05 * kHorseMeasured.flippedMax);
    EXPECT_EQ(s.foldedFacesMax, 0);
}
