// The real files in ../shared/data/c3d (see its README for what each holds).

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "C3dTestSupport.h"

using namespace boneless;

namespace {

double invalidShare(const C3dTake& t) {
    return double(t.samples.missingCount()) / double(t.frameCount() * t.points.size());
}

std::size_t pointsWithGaps(const C3dTake& t) {
    std::size_t n = 0;
    for (std::size_t k = 0; k < t.points.size(); ++k) n += t.samples.missingFrames(k) > 0;
    return n;
}

// "invalid" in the README is the share of negative residuals, so zeros are kept here.
C3dTake readKeepingZeros(const std::string& path) {
    C3dReadOptions o;
    o.keepZeroSamples = true;
    return readC3d(path, o);
}

// Same points, same validity, coordinates within tol (one int16 scale step when one is int16).
void expectSameData(const C3dTake& a, const C3dTake& b, double tol) {
    ASSERT_EQ(a.frameCount(), b.frameCount());
    ASSERT_EQ(a.points.size(), b.points.size());
    std::size_t compared = 0;
    for (std::size_t k = 0; k < a.points.size(); ++k) {
        ASSERT_EQ(a.points[k].label, b.points[k].label);
        for (std::size_t f = 0; f < a.frameCount(); ++f) {
            ASSERT_EQ(a.samples.valid(f, k), b.samples.valid(f, k))
                << a.file << " vs " << b.file << " frame " << f << " point " << k;
            const auto pa = a.samples.position(f, k), pb = b.samples.position(f, k);
            if (!pa) continue;
            ASSERT_LE((*pa - *pb).cwiseAbs().maxCoeff(), tol)
                << a.file << " vs " << b.file << " frame " << f << " point " << k;
            ++compared;
        }
    }
    EXPECT_GT(compared, a.frameCount() * a.points.size() / 2);
}

struct Encoding {
    const char* file;
    C3dProcessor processor;
    C3dStorage storage;
};

}  // namespace

namespace {

// What every encoding of one trial must agree on.
struct Trial {
    std::size_t frames, points;
    double invalidShare;
};

// Each file of an encoding matrix decodes to the reference's coordinates, within one scale step
// for int16 storage.
void expectEncodingsAgree(const std::string& folder, const Encoding (&encodings)[6],
                          const std::string& referenceFile, const Trial& trial) {
    const C3dTake reference = readKeepingZeros(folder + "/" + referenceFile);
    for (const auto& e : encodings) {
        SCOPED_TRACE(e.file);
        const C3dTake t = readKeepingZeros(folder + "/" + e.file);
        EXPECT_EQ(t.processor, e.processor);
        EXPECT_EQ(t.storage, e.storage);
        EXPECT_EQ(t.frameCount(), trial.frames);
        EXPECT_DOUBLE_EQ(t.rate, 50.0);
        EXPECT_EQ(t.points.size(), trial.points);
        EXPECT_EQ(t.analogChannels, 16);
        EXPECT_DOUBLE_EQ(t.analogRate, 200.0);
        EXPECT_EQ(t.units, "mm");
        EXPECT_EQ(t.firstFrameWord, 1);
        EXPECT_EQ(t.lastFrameWord, static_cast<int>(trial.frames));
        EXPECT_NEAR(invalidShare(t), trial.invalidShare, 0.0015);
        const double step = e.storage == C3dStorage::Int16 ? std::fabs(t.pointScale) : 1e-3;
        expectSameData(t, reference, step);
    }
}

}  // namespace

TEST(C3dSampleFiles, Sample01SixEncodingsAgree) {
    C3D_SHARED_OR_SKIP(s01, "c3d-org/sample01");
    const Encoding encodings[] = {{"Eb015pi.c3d", C3dProcessor::Intel, C3dStorage::Int16},
                                  {"Eb015pr.c3d", C3dProcessor::Intel, C3dStorage::Float},
                                  {"Eb015vi.c3d", C3dProcessor::Dec, C3dStorage::Int16},
                                  {"Eb015vr.c3d", C3dProcessor::Dec, C3dStorage::Float},
                                  {"Eb015si.c3d", C3dProcessor::Mips, C3dStorage::Int16},
                                  {"Eb015sr.c3d", C3dProcessor::Mips, C3dStorage::Float}};
    expectEncodingsAgree(s01, encodings, "Eb015pr.c3d", {450, 26, 0.019});
    EXPECT_EQ(pointsWithGaps(readKeepingZeros(s01 + "/Eb015pi.c3d")), 10u);
}

TEST(C3dSampleFiles, Sample02SixEncodingsAgree) {
    C3D_SHARED_OR_SKIP(s02, "c3d-org/sample02");
    const Encoding encodings[] = {{"pc_int.c3d", C3dProcessor::Intel, C3dStorage::Int16},
                                  {"pc_real.c3d", C3dProcessor::Intel, C3dStorage::Float},
                                  {"dec_int.c3d", C3dProcessor::Dec, C3dStorage::Int16},
                                  {"dec_real.c3d", C3dProcessor::Dec, C3dStorage::Float},
                                  {"sgi_int.c3d", C3dProcessor::Mips, C3dStorage::Int16},
                                  {"sgi_real.c3d", C3dProcessor::Mips, C3dStorage::Float}};
    expectEncodingsAgree(s02, encodings, "pc_real.c3d", {89, 36, 0.071});
}

TEST(C3dSampleFiles, Sample08ParameterSectionFollowsHeaderPointer) {
    C3D_SHARED_OR_SKIP(s08, "c3d-org/sample08");
    C3D_SHARED_OR_SKIP(s01, "c3d-org/sample01");
    const C3dTake reference = readC3d(s01 + "/Eb015pi.c3d");
    for (const char* name : {"TESTAPI.c3d", "TESTBPI.c3d", "TESTCPI.c3d", "TESTDPI.c3d"}) {
        SCOPED_TRACE(name);
        const C3dTake t = readC3d(s08 + "/" + name);
        EXPECT_EQ(t.frameCount(), 450u);
        EXPECT_EQ(t.points.size(), 26u);
        expectSameData(t, reference, 0.0);  // identical int16 data
    }
}

TEST(C3dSampleFiles, CorruptParameterSectionIsRejected) {
    C3D_SHARED_OR_SKIP(bad, "c3d-org/sample18/bad_parameter_section.c3d");
    try {
        readC3d(bad);
        FAIL() << "a corrupt parameter section was accepted";
    } catch (const C3dError& e) {
        EXPECT_EQ(e.file(), bad);
        EXPECT_NE(e.offset(), C3dError::kNoOffset);
        EXPECT_GT(e.offset(), 512u);  // inside the parameter section, past the header
        EXPECT_NE(std::string(e.what()).find("parameter"), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
}

TEST(C3dSampleFiles, EmptyFileIsRejected) {
    C3D_SHARED_OR_SKIP(empty, "btk/Empty.c3d");
    try {
        readC3d(empty);
        FAIL() << "an empty file was accepted";
    } catch (const C3dError& e) {
        EXPECT_EQ(e.offset(), 0u);
        EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("Empty.c3d"), std::string::npos) << e.what();
    }
}

TEST(C3dSampleFiles, MyCubeSmallestValidFile) {
    C3D_SHARED_OR_SKIP(cube, "btk/MyCube.c3d");
    const C3dTake t = readC3d(cube);
    EXPECT_EQ(t.frameCount(), 1u);
    EXPECT_DOUBLE_EQ(t.rate, 50.0);
    EXPECT_EQ(t.points.size(), 14u);
}

TEST(C3dSampleFiles, PluginGaitModelOutputsAreNotMarkers) {
    C3D_SHARED_OR_SKIP(pig, "btk/PiG_Motion-FlatFoot-Hole.c3d");
    const C3dTake t = readKeepingZeros(pig);
    EXPECT_EQ(t.frameCount(), 320u);
    EXPECT_DOUBLE_EQ(t.rate, 100.0);
    EXPECT_EQ(t.points.size(), 193u);
    EXPECT_EQ(t.analogChannels, 38);
    EXPECT_EQ(t.firstFrame, 143);  // TRIAL:ACTUAL_START_FIELD
    EXPECT_NEAR(invalidShare(t), 0.105, 0.0015);
    std::map<C3dPointKind, int> kinds;
    for (const auto& p : t.points) ++kinds[p.kind];
    EXPECT_EQ(kinds[C3dPointKind::Angle], 26);
    EXPECT_EQ(kinds[C3dPointKind::Force], 20);
    EXPECT_EQ(kinds[C3dPointKind::Moment], 18);
    EXPECT_EQ(kinds[C3dPointKind::Power], 16);
    EXPECT_EQ(kinds[C3dPointKind::Virtual], 78);  // 19 segments x 4 axis points + 2 centre of mass
    EXPECT_EQ(kinds[C3dPointKind::Marker], 35);
    EXPECT_EQ(t.markerIndices().size(), 35u);
    EXPECT_EQ(t.points[t.findPoint("LHipAngles").value()].kind, C3dPointKind::Angle);
    EXPECT_EQ(t.points[t.findPoint("PELO").value()].kind, C3dPointKind::Virtual);
    EXPECT_EQ(t.points[t.findPoint("LASI").value()].kind, C3dPointKind::Marker);
    EXPECT_EQ(t.parameters.find("POINT", "ANGLE_UNITS")->string(), "deg");
}

TEST(C3dSampleFiles, CmuDescriptionsMatchTheTable) {
    C3D_SHARED_OR_SKIP(cmu, "cmu/85_02.c3d");
    const C3dTake t = readC3d(cmu);
    EXPECT_EQ(t.frameCount(), 810u);
    EXPECT_DOUBLE_EQ(t.rate, 120.0);
    ASSERT_EQ(t.points.size(), 41u);
    EXPECT_EQ(t.samples.missingCount(), 0u);
    std::ifstream tsv(c3dtest::sharedC3d() / "cmu/cmu_41_marker_descriptions.tsv");
    ASSERT_TRUE(tsv);
    std::string line;
    int rows = 0;
    while (std::getline(tsv, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream in(line);
        std::string index, label, description;
        std::getline(in, index, '\t');
        std::getline(in, label, '\t');
        std::getline(in, description);
        const std::size_t i = std::stoul(index);
        ASSERT_LT(i, t.points.size());
        EXPECT_EQ(t.points[i].name, label);  // the table drops the "Male:" subject prefix
        EXPECT_EQ(t.points[i].subject, "Male");
        EXPECT_EQ(t.points[i].description, description);
        ++rows;
    }
    EXPECT_EQ(rows, 41);
}

TEST(C3dSampleFiles, ViconSubjectPrefixes) {
    C3D_SHARED_OR_SKIP(vicon, "ezc3d/Vicon.c3d");
    const C3dTake t = readC3d(vicon);
    EXPECT_EQ(t.frameCount(), 580u);
    EXPECT_DOUBLE_EQ(t.rate, 100.0);
    EXPECT_EQ(t.points.size(), 51u);
    EXPECT_EQ(t.analogChannels, 38);
    EXPECT_DOUBLE_EQ(t.analogRate, 2000.0);
    const auto box = t.findPoint("gauche_ext");
    ASSERT_TRUE(box);
    EXPECT_EQ(t.points[*box].subject, "boite");
    EXPECT_EQ(t.points[*box].label, "boite:gauche_ext");
    std::map<std::string, int> subjects;
    for (const auto& p : t.points) ++subjects[p.subject];
    EXPECT_EQ(subjects.size(), 2u);
    EXPECT_GT(subjects["boite"], 0);
    EXPECT_GT(subjects["Daphnee"], 0);
    EXPECT_GT(pointsWithGaps(t), 0u);
}

TEST(C3dSampleFiles, NumediartHeavyOcclusion) {
    C3D_SHARED_OR_SKIP(rolling, "numediart-gaps/03_rolling.c3d");
    // This exporter (Qualisys) writes gaps as (0,0,0) with a valid residual: the 23 % only
    // appears when such samples count as missing, the default.
    const C3dTake t = readC3d(rolling);
    EXPECT_EQ(t.frameCount(), 2305u);
    EXPECT_DOUBLE_EQ(t.rate, 175.0);
    EXPECT_EQ(t.points.size(), 68u);
    EXPECT_NEAR(invalidShare(t), 0.23, 0.005);
    EXPECT_EQ(pointsWithGaps(t), 67u);
    EXPECT_EQ(t.firstFrameWord, 1368);
    // Its POINT:Y_SCREEN says -Z, but its floor is at z = 0 and the actor above it.
    EXPECT_EQ(t.vertical, Eigen::Vector3d::UnitZ());
    const C3dTake kept = readKeepingZeros(rolling);
    EXPECT_EQ(kept.samples.missingCount(), 0u);
}

TEST(C3dSampleFiles, EveryFileReadsOrIsRejectedCleanly) {
    const auto root = c3dtest::sharedC3d();
    if (!std::filesystem::exists(root)) GTEST_SKIP() << "no shared data: " << root;
    int read = 0, rejected = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
        if (e.path().extension() != ".c3d") continue;
        const std::string name = e.path().filename().string();
        const bool corrupt = name == "Empty.c3d" || name == "bad_parameter_section.c3d";
        try {
            const C3dTake t = readC3d(e.path().string());
            EXPECT_FALSE(corrupt) << name << " was accepted";
            EXPECT_GT(t.frameCount(), 0u) << name;
            EXPECT_EQ(t.unitToMm, 1.0) << name;
            ++read;
        } catch (const C3dError& err) {
            EXPECT_TRUE(corrupt) << err.what();
            ++rejected;
        }
    }
    EXPECT_EQ(read, 21);
    EXPECT_EQ(rejected, 2);
}
