// readC3d reads a file a few megabytes at a time, never holding it whole beside its samples: what
// it gives must be what the same bytes read at once give (readC3dMemory).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "C3dTestSupport.h"

using namespace boneless;

namespace {

// Frame f's point k's x in a float file (Intel) whose 3D data starts at the header's block.
void setStoredX(std::vector<std::uint8_t>& bytes, std::size_t points, std::size_t f, std::size_t k,
                float x) {
    const std::size_t dataStart = (std::size_t(bytes[16]) | std::size_t(bytes[17]) << 8) - 1;
    std::memcpy(&bytes[dataStart * 512 + (f * points + k) * 16], &x, sizeof x);
}

}  // namespace

TEST(C3dFileReading, ATakeReadFromItsFileInPiecesIsTheTakeItsBytesHoldWhole) {
    // 40 points of floats, 640 bytes a frame: 9000 frames are read in two pieces of 4 MB and more.
    const std::size_t points = 40, frames = 9000;
    C3dTake t = c3dtest::syntheticTake(frames, c3dtest::numberedLabels(points));
    t.samples.set(6553, 5, 0.0, 0.0, 0.0, 1.0f);  // counted as missing, with a warning
    t.samples.set(8999, 39, 0.0, 0.0, 0.0, 1.0f);
    std::vector<std::uint8_t> bytes = encodeC3d(t);
    ASSERT_GT(bytes.size(), std::size_t(5) << 20);
    // A coordinate no writer writes, across the pieces' boundary from the zeros.
    ASSERT_TRUE(t.samples.valid(100, 8));
    setStoredX(bytes, points, 100, 8, std::numeric_limits<float>::infinity());
    const std::string path = (c3dtest::workDir() / "pieces.c3d").string();
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));

    const C3dTake fromFile = readC3d(path);
    const C3dTake fromBytes = readC3dMemory(bytes.data(), bytes.size(), path);
    ASSERT_EQ(fromFile.frameCount(), frames);
    EXPECT_TRUE(fromFile.samples.samePositions(fromBytes.samples));
    EXPECT_FALSE(fromFile.samples.valid(6553, 5));
    EXPECT_FALSE(fromFile.samples.valid(100, 8));
    EXPECT_TRUE(fromFile.samples.valid(100, 9));
    for (std::size_t f : {0u, 6552u, 6554u, 8999u})
        for (std::size_t k = 0; k < points; ++k)
            ASSERT_EQ(fromFile.samples.residual(f, k), fromBytes.samples.residual(f, k));
    EXPECT_EQ(fromFile.warnings, fromBytes.warnings);
    EXPECT_EQ(fromFile.vertical, fromBytes.vertical);
    EXPECT_EQ(fromFile.markerSpan.stored, fromBytes.markerSpan.stored);
    bool zeros = false, nonFinite = false;
    for (const std::string& w : fromFile.warnings) {
        zeros |= w.find("2 samples are exactly (0, 0, 0)") != std::string::npos;
        nonFinite |= w.find("1 samples have non-finite coordinates") != std::string::npos;
    }
    EXPECT_TRUE(zeros);
    EXPECT_TRUE(nonFinite);
}
