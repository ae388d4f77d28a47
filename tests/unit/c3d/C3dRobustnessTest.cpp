// Damaged files: every failure is a C3dError naming the file, never a crash or another exception.
// Run under AddressSanitizer (BONELESS_SANITIZE=ON) this also proves no out-of-bounds reads.

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "C3dTestSupport.h"

using namespace boneless;

namespace {

// Reads from an allocation of exactly size bytes so that a read past the end is caught.
enum class Outcome { Read, Rejected };
Outcome readExact(const std::vector<std::uint8_t>& bytes, std::size_t size) {
    std::unique_ptr<std::uint8_t[]> exact(new std::uint8_t[size ? size : 1]);
    std::copy(bytes.begin(), bytes.begin() + size, exact.get());
    try {
        const C3dTake t = readC3dMemory(exact.get(), size, "damaged.c3d");
        // Whatever was read must be self-consistent.
        EXPECT_EQ(t.samples.points(), t.points.size());
        return Outcome::Read;
    } catch (const C3dError& e) {
        EXPECT_EQ(e.file(), "damaged.c3d");
        EXPECT_EQ(std::string(e.what()).rfind("damaged.c3d: ", 0), 0u) << e.what();
        return Outcome::Rejected;
    }
}

std::vector<std::uint8_t> sampleFile() {
    C3dTake t = c3dtest::syntheticTake(6, {"s:A", "s:B", "C"});
    t.points[2].kind = C3dPointKind::Angle;
    t.firstFrame = 70000;  // forces the TRIAL group
    return encodeC3d(t);
}

}  // namespace

TEST(C3dRobustness, EveryTruncationReadsOrIsRejected) {
    const auto bytes = sampleFile();
    std::size_t rejected = 0;
    for (std::size_t n = 0; n <= bytes.size(); ++n)
        rejected += readExact(bytes, n) == Outcome::Rejected;
    EXPECT_EQ(readExact(bytes, bytes.size()), Outcome::Read);
    EXPECT_EQ(readExact(bytes, 0), Outcome::Rejected);
    EXPECT_GT(rejected, 512u);  // at least every cut inside the header
}

TEST(C3dRobustness, RandomByteDamageReadsOrIsRejected) {
    const auto original = sampleFile();
    const std::size_t dataStart = (original[16] | (original[17] << 8)) * 512 - 512;
    std::mt19937 rng(12345);
    std::size_t read = 0, rejected = 0;
    for (int trial = 0; trial < 5000; ++trial) {
        auto bytes = original;
        const int edits = 1 + int(rng() % 4);
        for (int e = 0; e < edits; ++e) {
            // Mostly the header and parameter section, where the structure is.
            const std::size_t at = (rng() % 4 == 0) ? rng() % bytes.size() : rng() % dataStart;
            bytes[at] = static_cast<std::uint8_t>(rng());
        }
        (readExact(bytes, bytes.size()) == Outcome::Read ? read : rejected)++;
    }
    // Both outcomes occur: the damage is neither all harmless nor all fatal.
    EXPECT_GT(read, 0u);
    EXPECT_GT(rejected, 0u);
}

TEST(C3dRobustness, HugeCountsAreBoundedByTheFile) {
    auto bytes = sampleFile();
    // Header: 65535 points, frames 1..65535; the parameters still say 3 points, 6 frames, so
    // the parameters win; without them the header's counts must be capped by the file size.
    bytes[2] = bytes[3] = 0xFF;
    bytes[6] = 1;
    bytes[7] = 0;
    bytes[8] = bytes[9] = 0xFF;
    EXPECT_EQ(readExact(bytes, bytes.size()), Outcome::Read);
    bytes[0] = 0;  // drop the parameter section: the header's 65535 x 65535 cannot fit
    EXPECT_EQ(readExact(bytes, bytes.size()), Outcome::Rejected);
}
