// What a take read whole costs in memory: a 25-minute take (112 MB) held the app at 825-860 MB,
// its samples as doubles with a byte of validity each, copied again for the solver.
#include <gtest/gtest.h>
#include <malloc.h>

#include <filesystem>

#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"
#include "boneless/DemoFiles.h"
#include "boneless/MarkerTrack.h"

using namespace boneless;

namespace {

// Bytes the heap has handed out (mmapped blocks included), over all arenas.
double heapBytes() {
    const struct mallinfo2 m = mallinfo2();
    return double(m.uordblks) + double(m.hblkhd);
}

// 20,000 frames of 40 markers seen with residuals, a few missing: a 12.8 MB float file.
std::string writeLongTake(const std::string& name) {
    C3dTake take;
    take.rate = 120;
    for (int k = 0; k < 40; ++k) {
        C3dPoint p;
        p.label = p.name = "M" + std::to_string(k);
        take.points.push_back(p);
    }
    take.samples = C3dSamples(20000, 40);
    for (std::size_t f = 0; f < 20000; ++f)
        for (std::size_t k = 0; k < 40; ++k)
            if ((f + k) % 97 != 0) take.samples.set(f, k, 10.0 * k, 0.25 * f, 1000 - 0.5 * f, 2.0f);
    const std::string path = (std::filesystem::path(freshTestDir(name)) / "long.c3d").string();
    writeC3d(take, path);
    return path;
}

}  // namespace

TEST(C3dTakeMemory, ATakeReadWholeHoldsNoMoreThanItsFile) {
    const std::string path = writeLongTake("C3dTakeMemory.ReadWhole");
    const double file = double(std::filesystem::file_size(path));
    const double before = heapBytes();
    const C3dTake take = readC3d(path);
    const double held = heapBytes() - before;
    EXPECT_EQ(take.frameCount(), 20000u);
    EXPECT_EQ(*take.samples.position(3, 5), Eigen::Vector3d(50, 0.75, 998.5));
    EXPECT_EQ(take.samples.residual(3, 5), 2.0f);
    EXPECT_LE(held, 1.05 * file) << "held " << held << " bytes for a file of " << file;
}

TEST(C3dTakeMemory, ACopyOfATakeSharesItsSamplesUntilOneChanges) {
    const std::string path = writeLongTake("C3dTakeMemory.Copy");
    const C3dTake take = readC3d(path);
    const double before = heapBytes();
    C3dTake copy = take;
    EXPECT_LE(heapBytes() - before, 0.01 * double(std::filesystem::file_size(path)));
    // Changing the copy leaves the original as read.
    copy.samples.setMissing(3, 5);
    EXPECT_FALSE(copy.samples.valid(3, 5));
    EXPECT_EQ(*take.samples.position(3, 5), Eigen::Vector3d(50, 0.75, 998.5));
    copy.samples.set(4, 5, 1, 2, 3);
    EXPECT_EQ(*copy.samples.position(4, 5), Eigen::Vector3d(1, 2, 3));
    EXPECT_EQ(*take.samples.position(4, 5), Eigen::Vector3d(50, 1, 998));
}

// The app's solver reads the take the document holds: unfiltered, it reads the take's samples
// rather than a copy of the mapped markers'.
TEST(C3dTakeMemory, AnUnfilteredTrackOfATakeInMemoryHoldsNoCopyOfIt) {
    const std::string path = writeLongTake("C3dTakeMemory.Track");
    const C3dTake take = readC3d(path);
    std::vector<std::size_t> points;
    for (std::size_t k = 0; k < 40; k += 2) points.push_back(k);
    const double before = heapBytes();
    const MarkerTrack track(take, points, 0.0);
    // Only the frames where some marker is seen (4 bytes a frame, against the file's 640).
    EXPECT_LE(heapBytes() - before, 0.02 * double(std::filesystem::file_size(path)));
    // Column 1 is point 2, which frame 95 misses ((95 + 2) % 97 == 0).
    const C3dSamples frames = track.read(3, 93);
    EXPECT_EQ(*frames.position(0, 1), *take.samples.position(3, 2));
    EXPECT_FALSE(frames.valid(92, 1));
    EXPECT_TRUE(frames.valid(92, 0));
}
