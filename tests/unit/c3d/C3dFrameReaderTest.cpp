// C3dFrameReader: a file read a range of frames at a time gives what readC3d gives.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "C3dTestSupport.h"
#include "boneless/C3dFrameReader.h"

using namespace boneless;

namespace {

std::string writeBytes(const std::string& name, const std::vector<std::uint8_t>& bytes) {
    const std::string path = (c3dtest::workDir() / name).string();
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return path;
}

void expectSameSamples(const C3dSamples& whole, std::size_t first, const C3dSamples& part) {
    for (std::size_t f = 0; f < part.frames(); ++f)
        for (std::size_t k = 0; k < part.points(); ++k) {
            ASSERT_EQ(part.valid(f, k), whole.valid(first + f, k)) << f << ", " << k;
            if (part.valid(f, k))
                ASSERT_EQ(*part.position(f, k), *whole.position(first + f, k)) << f << ", " << k;
        }
}

}  // namespace

// Any range, the last frames and none included, holds the samples of the file read whole, and
// the take's description is the same.
TEST(C3dFrameReader, AnyRangeOfFramesHoldsTheSamplesOfTheFileReadWhole) {
    const std::string path = writeBytes(
        "frames.c3d", encodeC3d(c3dtest::syntheticTake(300, c3dtest::numberedLabels(9))));
    const C3dTake whole = readC3d(path);
    const C3dFrameReader reader(path);
    ASSERT_EQ(reader.frameCount(), 300u);
    EXPECT_EQ(reader.take().points.size(), whole.points.size());
    EXPECT_EQ(reader.take().points[4].label, whole.points[4].label);
    EXPECT_EQ(reader.take().rate, whole.rate);
    EXPECT_EQ(reader.take().warnings, whole.warnings);
    for (auto [first, count] :
         {std::pair<std::size_t, std::size_t>{0, 300}, {17, 50}, {299, 1}, {300, 0}}) {
        const C3dSamples part = reader.read(first, count);
        ASSERT_EQ(part.frames(), count);
        expectSameSamples(whole.samples, first, part);
    }
    EXPECT_THROW(reader.read(290, 11), std::out_of_range);
}

// A truncated file: the complete frames, with readC3d's warning; a damaged one is refused with
// readC3d's message.
TEST(C3dFrameReader, KeepsAndRefusesWhatReadC3dKeepsAndRefuses) {
    std::vector<std::uint8_t> bytes = encodeC3d(c3dtest::syntheticTake(40, {"A", "B"}));
    bytes.resize(bytes.size() - 40);  // the last frames are cut
    const std::string cut = writeBytes("cut.c3d", bytes);
    const C3dTake whole = readC3d(cut);
    const C3dFrameReader reader(cut);
    ASSERT_LT(whole.frameCount(), 40u);
    EXPECT_EQ(reader.frameCount(), whole.frameCount());
    EXPECT_EQ(reader.take().warnings, whole.warnings);
    expectSameSamples(whole.samples, 0, reader.read(0, reader.frameCount()));

    bytes[1] = 0x42;  // not the C3D key
    const std::string damaged = writeBytes("damaged.c3d", bytes);
    std::string wholeMessage, streamedMessage;
    try {
        readC3d(damaged);
    } catch (const C3dError& e) {
        wholeMessage = e.what();
    }
    try {
        C3dFrameReader{damaged};
    } catch (const C3dError& e) {
        streamedMessage = e.what();
    }
    EXPECT_NE(wholeMessage.find("damaged.c3d"), std::string::npos) << wholeMessage;
    EXPECT_EQ(streamedMessage, wholeMessage);
    EXPECT_THROW(C3dFrameReader{(c3dtest::workDir() / "absent.c3d").string()}, C3dError);
}
