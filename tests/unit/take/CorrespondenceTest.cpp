#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "TestFiles.h"
#include "boneless/C3dTake.h"
#include "boneless/Correspondence.h"
#include "boneless/Error.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

const char* kValid = R"({"format": "boneless-correspondence", "version": 1,
  "mesh": {"file": "body.obj", "vertices": 100, "units": "dm"},
  "author": "test",
  "markers": [{"label": "LFHD", "vertex": 12, "offset_mm": 9.5, "note": "left front head"},
              {"label": "RFHD", "vertex": 40}]})";

// A take `file` holding markers labelled `labels`, without samples: what resolve() reads.
C3dTake takeOf(const char* file, std::initializer_list<const char*> labels) {
    C3dTake take;
    take.file = file;
    for (const char* label : labels) {
        C3dPoint p;
        p.label = label;
        splitC3dLabel(label, p.subject, p.name);
        take.points.push_back(p);
    }
    return take;
}

}  // namespace

TEST(Correspondence, ReadsTheDocumentedFormat) {
    const Correspondence c = Correspondence::read(writeTestFile("valid.json", kValid));
    EXPECT_EQ(c.meshFile, "body.obj");
    EXPECT_EQ(c.meshVertices, 100);
    ASSERT_EQ(c.markers.size(), 2u);
    EXPECT_EQ(c.markers[0].label, "LFHD");
    EXPECT_EQ(c.markers[0].vertex, 12);
    EXPECT_DOUBLE_EQ(c.markers[0].offsetMm, 9.5);
    EXPECT_DOUBLE_EQ(c.markers[1].offsetMm, 0.0);
}

TEST(Correspondence, KeepsUnknownKeysOnRewrite) {
    Correspondence c = Correspondence::read(writeTestFile("extra.json", kValid));
    c.markers[1].vertex = 41;
    const std::string out = writeTestFile("rewritten.json", "");
    c.write(out);
    const auto j = nlohmann::json::parse(std::ifstream(out));
    EXPECT_EQ(j["author"], "test");
    EXPECT_EQ(j["mesh"]["units"], "dm");
    EXPECT_EQ(j["markers"][0]["note"], "left front head");
    EXPECT_EQ(j["markers"][1]["vertex"], 41);
    const Correspondence back = Correspondence::read(out);
    EXPECT_EQ(back.markers[1].vertex, 41);
    EXPECT_EQ(back.toJson(), c.toJson());
}

TEST(Correspondence, RejectsBadFilesNamingFileAndEntry) {
    std::string e = errorOf([] { Correspondence::read(writeTestFile("bad.json", "{not json")); });
    EXPECT_NE(e.find("bad.json"), std::string::npos);
    EXPECT_NE(e.find("not valid JSON"), std::string::npos) << e;

    e = errorOf([] {
        Correspondence::read(writeTestFile("dup.json", R"({"format": "boneless-correspondence",
          "version": 1, "markers": [{"label": "A", "vertex": 3}, {"label": "B", "vertex": 3}]})"));
    });
    EXPECT_NE(e.find("marker B: vertex 3 already carries marker A"), std::string::npos) << e;

    e = errorOf([] {
        Correspondence::read(writeTestFile("v3.json", R"({"format": "boneless-correspondence",
          "version": 3, "markers": []})"));
    });
    EXPECT_NE(e.find("version 3"), std::string::npos) << e;

    e = errorOf([] {
        Correspondence::read(writeTestFile("nolabel.json", R"({"format": "boneless-correspondence",
          "version": 1, "markers": [{"vertex": 3}]})"));
    });
    EXPECT_NE(e.find("markers[0] has no \"label\""), std::string::npos) << e;
}

// An entry was "marker 1:" in one message, "marker 1 (T10):" in the next and "marker T10:" in
// checkMesh's, and "marker 1" could be a label. Every message names it by its label, as the user
// wrote it; by its place in "markers" only while it has no label, and beside it where two entries
// share one.
TEST(Correspondence, EveryMessageNamesAnEntryByItsLabel) {
    const auto error = [](const std::string& markers) {
        const std::string path = writeTestFile("named.json",
                                               R"({"format": "boneless-correspondence",
          "version": 2, "markers": [)" + markers + "]}");
        return errorOf([&] { Correspondence::read(path); }).substr(path.size());
    };
    EXPECT_EQ(
        error(R"({"label": "A", "vertex": 1}, {"label": "T10", "vertex": 2, "offset_mm": 5000})"),
        ": marker T10: \"offset_mm\" 5000 is out of range (a marker sits -50 to 200 mm off "
        "the skin)");
    EXPECT_EQ(error(R"({"label": "A", "vertex": 1}, {"label": "T10", "vertex": -1})"),
              ": marker T10: vertex -1 is negative");
    EXPECT_EQ(error(R"({"label": "A", "vertex": 1}, {"label": "T10", "vertex": 1})"),
              ": marker T10: vertex 1 already carries marker A");
    EXPECT_EQ(error(R"({"label": "T10", "vertex": 1}, {"label": "B", "vertex": 2},
                       {"label": "T10", "vertex": 3})"),
              ": marker T10 is mapped twice (markers[0] and markers[2])");
    EXPECT_EQ(error(R"({"label": "T10", "vertex": "one"})"),
              ": marker T10: \"vertex\" is not a whole number in the int range");
    EXPECT_EQ(error(R"({"label": "T10"})"), ": marker T10 has no \"vertex\"");
    EXPECT_EQ(error(R"({"label": "A", "vertex": 1}, {"label": "T10", "vertex": 2, "face": 0,
                       "barycentric": [2, 0, 0]})"),
              ": marker T10: \"barycentric\" must be three numbers, none negative, that sum to 1");
    EXPECT_EQ(error(R"({"label": "A", "vertex": 1}, 7)"), ": markers[1] is not an object");
    EXPECT_EQ(error(R"({"label": "A", "vertex": 1}, {"vertex": 2})"),
              ": markers[1] has no \"label\"");
    const Correspondence far = Correspondence::fromJson(
        R"({"format": "boneless-correspondence", "version": 1,
            "markers": [{"label": "T10", "vertex": 40}]})",
        "far.json");
    EXPECT_EQ(errorOf([&] { far.checkMesh(10, "body.obj"); }),
              "far.json: marker T10: vertex 40 is out of range (body.obj has 10 vertices)");
}

// "face" and "barycentric" are read from version 2 on. A version 1 file that gave an entry a face
// number (written by hand, or by a tool that did not raise the version) loaded with it ignored in
// silence: the marker sat on its vertex. It still does, as version 1 promises, and the map says
// so, naming the file and the entries; a "face" that is no face number is a key of its own.
TEST(Correspondence, AVersion1EntryWithAFaceNumberIsReadWithAWarningNamingIt) {
    const std::string path = writeTestFile("v1face.json", R"({"format": "boneless-correspondence",
      "version": 1, "markers": [{"label": "A", "vertex": 3, "face": 12,
                                 "barycentric": [0.5, 0.5, 0]},
                                {"label": "B", "vertex": 4, "face": "left"},
                                {"label": "T10", "vertex": 5, "face": 7}]})");
    const Correspondence c = Correspondence::read(path);
    EXPECT_EQ(c.markers[0].face, -1);
    ASSERT_EQ(c.warnings.size(), 1u);
    EXPECT_EQ(c.warnings[0], path +
                                 ": marker A has \"face\": 12; marker T10 has \"face\": 7, which "
                                 "only \"version\": 2 reads: this file says \"version\": 1, so "
                                 "they sit on their \"vertex\" (write \"version\": 2 to place "
                                 "them on the face)");
    const Correspondence left = Correspondence::fromJson(
        R"({"format": "boneless-correspondence", "version": 1,
            "markers": [{"label": "A", "vertex": 3, "face": "left"}]})",
        "left.json");
    EXPECT_TRUE(left.warnings.empty());
}

// Such a map, once one marker is put on a face point (a click in the app), is written as version
// 2, where the other entries' own "face" keys would be read: T10's, without a "barycentric", made
// the file (and the project holding it) unreadable. They keep sitting on their vertices.
TEST(Correspondence, AVersion1EntrysFaceKeyIsNotCarriedIntoAVersion2Map) {
    Correspondence c = Correspondence::fromJson(R"({"format": "boneless-correspondence",
      "version": 1, "markers": [{"label": "A", "vertex": 3, "face": 12,
                                 "barycentric": [0.5, 0.5, 0]},
                                {"label": "B", "vertex": 4, "face": "left"},
                                {"label": "T10", "vertex": 5, "face": 7}]})",
                                                "v1face.json");
    EXPECT_NE(c.toJson().find("\"face\": 7"), std::string::npos)
        << "version 1 keeps its own keys as they were";
    c.markers[1].face = 2;
    c.markers[1].barycentric = {0.2, 0.3, 0.5};
    const Correspondence again = Correspondence::fromJson(c.toJson(), "again.json");
    ASSERT_EQ(again.markers.size(), 3u);
    EXPECT_EQ(again.markers[0].face, -1);
    EXPECT_EQ(again.markers[0].vertex, 3);
    EXPECT_EQ(again.markers[1].face, 2);
    EXPECT_EQ(again.markers[2].face, -1);
    EXPECT_EQ(again.markers[2].vertex, 5);
    EXPECT_TRUE(again.warnings.empty());
}

TEST(Correspondence, ChecksTheMeshAndTheTake) {
    const Correspondence c = Correspondence::read(writeTestFile("valid2.json", kValid));
    EXPECT_NO_THROW(c.checkMesh(100, "body.obj"));
    EXPECT_NE(errorOf([&] { c.checkMesh(99, "other.obj"); }).find("99"), std::string::npos);

    C3dTake take = takeOf("take.c3d", {"actor:RFHD", "actor:LFHD", "actor:C7"});
    const auto points = c.resolve(take);
    EXPECT_EQ(points, (std::vector<std::size_t>{1, 0}));  // prefixes ignored, file order kept
    take.points.erase(take.points.begin());
    const std::string e = errorOf([&] { c.resolve(take); });
    EXPECT_NE(e.find("RFHD"), std::string::npos) << e;
    EXPECT_NE(e.find("take.c3d"), std::string::npos) << e;
}

TEST(Correspondence, AMapMadeOnAGroupSaysSoWhenTheWholeFileIsGiven) {
    std::string text = kValid;
    text.replace(text.find("\"vertices\""), 0, "\"group\": \"body\", ");
    const Correspondence c = Correspondence::read(writeTestFile("group.json", text));
    EXPECT_EQ(c.meshGroup, "body");
    const std::string e = errorOf([&] { c.checkMesh(19158, "makehuman_base.obj"); });
    EXPECT_NE(e.find("group 'body' of body.obj"), std::string::npos) << e;
    EXPECT_NE(e.find("with 100 vertices, but makehuman_base.obj has 19158"), std::string::npos)
        << e;
    // The group is written back, and not twice.
    const auto j = nlohmann::json::parse(c.toJson());
    EXPECT_EQ(j["mesh"]["group"], "body");
    EXPECT_EQ(Correspondence::fromJson(c.toJson(), "again").meshGroup, "body");
    EXPECT_EQ(nlohmann::json::parse(
                  Correspondence::read(writeTestFile("valid3.json", kValid)).toJson())["mesh"]
                  .count("group"),
              0u);
}

TEST(Correspondence, FromJsonTextMatchesTheFileAndNamesItsSource) {
    Correspondence c;
    c.meshFile = "body.obj";
    c.meshVertices = 10;
    c.markers.push_back({"LFHD", 3, 9.5, "{}"});
    const Correspondence back = Correspondence::fromJson(c.toJson(), "project.boneless");
    EXPECT_EQ(back.toJson(), c.toJson());
    // Wrong types are the user's mistake too: a message naming the source, not a JSON exception.
    for (
        const char* text :
        {R"({"format": 1})",
         R"({"format": "boneless-correspondence", "version": 1, "mesh": {"file": 3}, "markers": []})",
         R"({"format": "boneless-correspondence", "version": 1,
              "markers": [{"label": "A", "vertex": 1, "offset_mm": "ten"}]})"}) {
        try {
            Correspondence::fromJson(text, "project.boneless");
            ADD_FAILURE() << "accepted " << text;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("project.boneless"), std::string::npos)
                << e.what();
        }
    }
}

TEST(Correspondence, AnOffsetNoMarkerSitsAtIsRefusedNamingTheEntryAndTheValue) {
    for (const char* offset : {"-500", "5000", "200.5"}) {
        const std::string text = std::string(R"({"format": "boneless-correspondence",
          "version": 1, "markers": [{"label": "RFHD", "vertex": 3},
                                    {"label": "LFHD", "vertex": 4, "offset_mm": )") +
                                 offset + "}]}";
        const std::string e =
            errorOf([&] { Correspondence::read(writeTestFile("offset.json", text)); });
        EXPECT_NE(e.find("offset.json: marker LFHD: \"offset_mm\" " + std::string(offset)),
                  std::string::npos)
            << e;
        EXPECT_NE(e.find("-50 to 200 mm"), std::string::npos) << e;
    }
    // The ends of the range, and a marker a little under a clothed mesh's surface, still read.
    for (const char* offset : {"-50", "-5", "200"})
        EXPECT_NO_THROW(Correspondence::fromJson(
            std::string(R"({"format": "boneless-correspondence", "version": 1,
              "markers": [{"label": "A", "vertex": 1, "offset_mm": )") +
                offset + "}]}",
            "in range"));
}

TEST(Correspondence, ALabelNamingAModelOutputIsNoMarker) {
    const Correspondence c = Correspondence::read(writeTestFile("angle.json", R"({
      "format": "boneless-correspondence", "version": 1,
      "markers": [{"label": "LFHD", "vertex": 1}, {"label": "LKneeAngles", "vertex": 2}]})"));
    C3dTake take;
    take.file = "gait.c3d";
    for (const auto& [label, kind] :
         {std::pair{"LFHD", C3dPointKind::Marker}, std::pair{"LKneeAngles", C3dPointKind::Angle}}) {
        C3dPoint p;
        p.label = label;
        p.kind = kind;
        splitC3dLabel(label, p.subject, p.name);
        take.points.push_back(p);
    }
    const std::string e = errorOf([&] { c.resolve(take); });
    EXPECT_NE(e.find("angle.json: marker LKneeAngles names an angle point of gait.c3d"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("not a marker"), std::string::npos) << e;
}

TEST(Correspondence, ABareLabelTwoSubjectsWearIsRefusedAskingForTheSubject) {
    const C3dTake take = takeOf("pair.c3d", {"A:ASISr", "B:ASISr", "A:LFHD"});
    const auto mapOf = [](const char* label) {
        return Correspondence::fromJson(std::string(R"({"format": "boneless-correspondence",
          "version": 1, "markers": [{"label": "LFHD", "vertex": 1}, {"label": ")") +
                                            label + R"(", "vertex": 2}]})",
                                        "pair.json");
    };
    const std::string e = errorOf([&] { mapOf("ASISr").resolve(take); });
    EXPECT_NE(e.find("pair.json: marker ASISr is worn by more than one subject in pair.c3d "
                     "(A:ASISr, B:ASISr); write the subject prefix"),
              std::string::npos)
        << e;
    EXPECT_EQ(mapOf("B:ASISr").resolve(take), (std::vector<std::size_t>{2, 1}));
}

// Two points of a take with one full label are not two subjects: the advice to write the subject
// prefix led to "Male:LFWT", which bound silently to the first of them.
TEST(Correspondence, ALabelTwoPointsOfTheTakeShareIsRefusedNamingBothPoints) {
    const C3dTake take = takeOf("twice.c3d", {"Male:LFHD", "Male:LFWT", "Male:RFWT", "Male:LFWT"});
    const auto mapOf = [](const char* label) {
        return Correspondence::fromJson(std::string(R"({"format": "boneless-correspondence",
          "version": 1, "markers": [{"label": "LFHD", "vertex": 1}, {"label": ")") +
                                            label + R"(", "vertex": 2}]})",
                                        "twice.json");
    };
    for (const char* label : {"LFWT", "Male:LFWT", "male:lfwt"}) {
        const std::string e = errorOf([&] { mapOf(label).resolve(take); });
        EXPECT_NE(e.find(std::string("twice.json: marker ") + label +
                         ": in twice.c3d, points 1 and 3 are both labelled Male:LFWT"),
                  std::string::npos)
            << e;
        EXPECT_NE(e.find("two points with one label, not two subjects"), std::string::npos) << e;
    }
    EXPECT_EQ(mapOf("RFWT").resolve(take), (std::vector<std::size_t>{0, 2}));
}

// A prefix that names a subject of the take who does not wear the marker said only "not found":
// the marker's wearer is named.
TEST(Correspondence, ALabelPrefixedWithASubjectWhoDoesNotWearItNamesWhoDoes) {
    const C3dTake take = takeOf("vicon.c3d", {"Daphnee:LFHD", "boite:gauche_ext", "boite:dos"});
    const Correspondence map = Correspondence::fromJson(
        R"({"format": "boneless-correspondence", "version": 1, "markers": [
          {"label": "LFHD", "vertex": 1}, {"label": "Daphnee:gauche_ext", "vertex": 2}]})",
        "vicon.json");
    const std::string e = errorOf([&] { map.resolve(take); });
    EXPECT_NE(e.find("vicon.json: labels not found in vicon.c3d: Daphnee:gauche_ext; "
                     "boite:gauche_ext is in the take"),
              std::string::npos)
        << e;
}

// "LFHD" and "walker:lfhd" name one marker of the take: both entries bound to it, so one marker
// pulled two vertices and the sidecar counted 40 markers of a 39-marker take.
TEST(Correspondence, TwoEntriesNamingOneMarkerOfTheTakeAreRefusedNamingBoth) {
    const C3dTake take = takeOf("walk.c3d", {"walker:LFHD", "walker:RFHD"});
    const auto mapOf = [](const char* second) {
        return Correspondence::fromJson(std::string(R"({"format": "boneless-correspondence",
          "version": 1, "markers": [{"label": "LFHD", "vertex": 1}, {"label": ")") +
                                            second + R"(", "vertex": 2}]})",
                                        "walk.json");
    };
    for (const char* second : {"walker:LFHD", "lfhd"}) {
        const std::string e = errorOf([&] { mapOf(second).resolve(take); });
        EXPECT_NE(e.find(std::string("walk.json: marker LFHD and marker ") + second +
                         " both name walker:LFHD of walk.c3d"),
                  std::string::npos)
            << e;
    }
    EXPECT_EQ(mapOf("RFHD").resolve(take), (std::vector<std::size_t>{0, 1}));
}

// A fourth barycentric number was dropped on rewrite, a "barycentric" without "face" was read as
// nothing and dropped too, an empty label named nothing ("labels not found in walk.c3d: "), and
// a version of the wrong type was "the file: ...".
TEST(Correspondence, AFacePointOrLabelThatSaysNothingWholeIsRefused) {
    const auto error = [](const std::string& version, const std::string& entry) {
        return errorOf([&] {
            Correspondence::fromJson(R"({"format": "boneless-correspondence", "version": )" +
                                         version + R"(, "markers": [)" + entry + "]}",
                                     "m.json");
        });
    };
    EXPECT_NE(error("2", R"({"label": "A", "vertex": 1, "face": 0,
                             "barycentric": [0.2, 0.2, 0.6, 5]})")
                  .find("m.json: marker A: \"barycentric\" must be three numbers"),
              std::string::npos);
    EXPECT_NE(error("2", R"({"label": "A", "vertex": 1, "barycentric": [0.2, 0.2, 0.6]})")
                  .find("m.json: marker A: \"barycentric\" places it on a face, and it names no "
                        "\"face\""),
              std::string::npos);
    EXPECT_NE(
        error("1", R"({"label": "", "vertex": 1})").find("m.json: markers[0]: \"label\" is empty"),
        std::string::npos);
    EXPECT_NE(error("\"1\"", "").find("m.json: \"version\" is not a whole number"),
              std::string::npos)
        << error("\"1\"", "");
    EXPECT_EQ(
        error("2", R"({"label": "A", "vertex": 1, "face": 0, "barycentric": [0.2, 0.2, 0.6]})"),
        "");
}
