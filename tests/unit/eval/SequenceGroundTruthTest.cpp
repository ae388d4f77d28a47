#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

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
    EXPECT_LE(s.flippedFacesWorstFrame, boneless.flippedMax);
    EXPECT_EQ(s.foldedFacesWorstFrame, 0);  // turned away from the truth, perhaps, but never folded
    // The reference: libigl's ARAP with the same markers. Boneless must not be worse.
    EXPECT_LE(s.rmsPctMean, arapReference.rmsMean);
    EXPECT_LE(s.rmsPctWorstFrame, arapReference.rmsWorst);
    EXPECT_LE(s.flippedFacesWorstFrame, arapReference.flippedMax);
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

// docs/eval.md argues that a sequence which folds itself is folded in a faithful answer too, with
// the horse at 8430 of its 8431 vertices as markers; it quoted "folded max 5" where eval prints 27,
// the truth's own 27. The figures quoted are eval's summary as it prints them.
TEST(SequenceGroundTruth, TheHorseWithAllButOneVertexAsMarkersFoldsAsItsTruthAsTheDocsQuote) {
    const std::string folder = unpacked("horse-gallop/horse-gallop.tar.xz", "horse-gallop");
    if (folder.empty()) GTEST_SKIP() << "no shared data (" << BONELESS_SHARED_DATA << ")";
    const MeshSequence sequence = readMeshSequence(folder);
    EvaluationOptions options;
    options.markers = geodesicFarthestPoints(sequence.rest, sequence.rest.vertexCount() - 1, 0);
    const EvaluationSummary s = evaluateSequence(sequence, options).summary;
    EXPECT_EQ(s.foldedFacesWorstFrame, s.truthFoldedFacesWorstFrame);
    char rms[64], folded[64];
    std::snprintf(rms, sizeof rms, "RMS %% mean %.3f", s.rmsPctMean);
    std::snprintf(folded, sizeof folded, "folded max %d (truth folded max %d)",
                  s.foldedFacesWorstFrame, s.truthFoldedFacesWorstFrame);
    std::ifstream in(std::string(BONELESS_SOURCE_DIR) + "/docs/eval.md");
    ASSERT_TRUE(in) << "docs/eval.md is missing";
    std::stringstream docs;
    docs << in.rdbuf();
    // The docs wrap lines: compare with every run of spaces and line breaks made one space.
    std::string text;
    for (char c : docs.str()) {
        if (c == '\n') c = ' ';
        if (c != ' ' || text.empty() || text.back() != ' ') text += c;
    }
    const std::size_t at = text.find("--markers 8430");
    ASSERT_NE(at, std::string::npos) << "docs/eval.md no longer gives the horse at 8430 markers";
    const std::string quoted = text.substr(at, 400);
    EXPECT_NE(quoted.find(rms), std::string::npos) << rms << " in: " << quoted;
    EXPECT_NE(quoted.find(folded), std::string::npos) << folded << " in: " << quoted;
}
