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

// Measured with the default evaluation options (the local/global method), K = 40, every frame:
// horse 0.948 % mean, 1.327 % worst frame, 158 flipped faces at most; samba 0.859 %, 1.237 %,
// 259. The RMS bounds add about 4 % for floating-point differences between machines. Flips
// turn on a thin leg's twist, which a last bit can change by a hundred faces: their bound is
// the issue's, ARAP's own count.
constexpr Bound kHorseBound{0.99, 1.40, 305};
constexpr Bound kSambaBound{0.89, 1.28, 554};

Evaluation evaluateAtFortyMarkers(const MeshSequence& sequence) {
    EvaluationOptions options;
    options.markers = geodesicFarthestPoints(sequence.rest, 40, 0);
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
