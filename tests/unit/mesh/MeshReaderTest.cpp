#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include "boneless/Error.h"
#include "boneless/MeshReader.h"

using namespace boneless;
namespace fs = std::filesystem;

namespace {

using Polygons = std::vector<std::vector<int>>;

std::string workPath(const std::string& name) {
    const fs::path dir = fs::path(BONELESS_TEST_WORK_DIR) / "mesh-reader";
    fs::create_directories(dir);
    return (dir / name).string();
}

std::string writeFile(const std::string& name, const std::string& bytes) {
    const std::string path = workPath(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

template <typename T>
void put(std::string& out, T value) {
    out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

std::string objText(const Positions& V, const Polygons& P) {
    std::ostringstream s;
    s.precision(17);
    for (int i = 0; i < V.rows(); ++i)
        s << "v " << V(i, 0) << ' ' << V(i, 1) << ' ' << V(i, 2) << '\n';
    for (const auto& f : P) {
        s << 'f';
        for (int v : f) s << ' ' << v + 1;
        s << '\n';
    }
    return s.str();
}

std::string offText(const Positions& V, const Polygons& P) {
    std::ostringstream s;
    s.precision(17);
    s << "OFF\n# comment\n" << V.rows() << ' ' << P.size() << " 0\n";
    for (int i = 0; i < V.rows(); ++i) s << V(i, 0) << ' ' << V(i, 1) << ' ' << V(i, 2) << '\n';
    for (const auto& f : P) {
        s << f.size();
        for (int v : f) s << ' ' << v;
        s << '\n';
    }
    return s.str();
}

// OpenMesh's binary OFF: the keyword line, then little-endian 32-bit counts, floats and indices.
std::string offBinary(const Positions& V, const Polygons& P) {
    std::string s = "OFF BINARY\n";
    for (uint32_t n : {uint32_t(V.rows()), uint32_t(P.size()), 0u}) put(s, n);
    for (int i = 0; i < V.rows(); ++i)
        for (int k = 0; k < 3; ++k) put(s, float(V(i, k)));
    for (const auto& f : P) {
        put(s, uint32_t(f.size()));
        for (int v : f) put(s, uint32_t(v));
    }
    return s;
}

std::string plyHeader(const char* format, int nv, size_t nf) {
    return std::string("ply\nformat ") + format + " 1.0\ncomment made by a test\nelement vertex " +
           std::to_string(nv) +
           "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
           "element face " +
           std::to_string(nf) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string plyAscii(const Positions& V, const Polygons& P) {
    std::ostringstream s;
    s.precision(9);
    s << plyHeader("ascii", int(V.rows()), P.size());
    for (int i = 0; i < V.rows(); ++i) s << V(i, 0) << ' ' << V(i, 1) << ' ' << V(i, 2) << " 200\n";
    for (const auto& f : P) {
        s << f.size();
        for (int v : f) s << ' ' << v;
        s << '\n';
    }
    return s.str();
}

std::string plyBinary(const Positions& V, const Polygons& P) {
    std::string s = plyHeader("binary_little_endian", int(V.rows()), P.size());
    for (int i = 0; i < V.rows(); ++i) {
        for (int k = 0; k < 3; ++k) put(s, float(V(i, k)));
        put(s, uint8_t(200));
    }
    for (const auto& f : P) {
        put(s, uint8_t(f.size()));
        for (int v : f) put(s, int32_t(v));
    }
    return s;
}

std::string stlAscii(const Positions& V, const Faces& F) {
    std::ostringstream s;
    s.precision(9);
    s << "solid test\n";
    for (int t = 0; t < F.rows(); ++t) {
        s << "  facet normal 0 0 1\n    outer loop\n";
        for (int k = 0; k < 3; ++k)
            s << "      vertex " << V(F(t, k), 0) << ' ' << V(F(t, k), 1) << ' ' << V(F(t, k), 2)
              << '\n';
        s << "    endloop\n  endfacet\n";
    }
    return s.str() + "endsolid test\n";
}

std::string stlBinary(const Positions& V, const Faces& F) {
    std::string s(80, ' ');
    put(s, uint32_t(F.rows()));
    for (int t = 0; t < F.rows(); ++t) {
        for (int k = 0; k < 3; ++k) put(s, 0.0f);
        for (int k = 0; k < 9; ++k) put(s, float(V(F(t, k / 3), k % 3)));
        put(s, uint16_t(0));
    }
    return s;
}

// An open pyramid (no floor): 4 triangles around the apex, which is the *last* vertex in the
// file but the first corner of every face, so file order and first-use order differ.
Positions tentV() {
    Positions V(5, 3);
    V << 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0, 0, 0, 0.5;
    return V;
}
const Polygons tentP = {{4, 0, 1}, {4, 1, 2}, {4, 2, 3}, {4, 3, 0}};

Faces toFaces(const Polygons& P) {
    Faces F(P.size(), 3);
    for (size_t t = 0; t < P.size(); ++t) F.row(t) << P[t][0], P[t][1], P[t][2];
    return F;
}

// Runs `read`, expects a MeshError and returns its message after checking it names the file.
std::string errorOf(const std::string& path, const std::function<void()>& read) {
    try {
        read();
    } catch (const MeshError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        EXPECT_EQ(e.file(), path);
        return msg;
    }
    ADD_FAILURE() << "no MeshError for " << path;
    return {};
}

std::string errorOf(const std::string& path) {
    return errorOf(path, [&] { readMesh(path); });
}

#define EXPECT_CONTAINS(text, part)                            \
    EXPECT_NE(std::string(text).find(part), std::string::npos) \
        << "'" << (text) << "' lacks '" << (part) << "'"

bool anyWarningContains(const MeshReadResult& r, const std::string& part) {
    for (const auto& w : r.warnings)
        if (w.find(part) != std::string::npos) return true;
    return false;
}

std::string dataPath(const std::string& relative) {
    return (fs::path(BONELESS_SHARED_DATA) / relative).string();
}

}  // namespace

// ---- Formats and vertex order ----------------------------------------------------------------

TEST(MeshReaderFormats, EveryFormatKeepsTheFileVertexOrderAndFaces) {
    const Positions V = tentV();
    const std::map<std::string, std::string> files = {{"tent.obj", objText(V, tentP)},
                                                      {"tent.off", offText(V, tentP)},
                                                      {"tent_ascii.ply", plyAscii(V, tentP)},
                                                      {"tent_binary.ply", plyBinary(V, tentP)}};
    for (const auto& [name, bytes] : files) {
        SCOPED_TRACE(name);
        const MeshReadResult r = readMesh(writeFile(name, bytes));
        EXPECT_EQ(r.mesh.V, V);  // values are exact in float, so even OpenMesh's floats match
        EXPECT_EQ(r.mesh.F, toFaces(tentP));
        EXPECT_EQ(r.sourceVertexCount, 5);
        EXPECT_EQ(r.sourceVertexIndex, (std::vector<int>{0, 1, 2, 3, 4}));
        EXPECT_EQ(r.sourceFaceIndex, (std::vector<int>{0, 1, 2, 3}));
    }
}

TEST(MeshReaderFormats, StlVerticesComeInOrderOfFirstAppearance) {
    const Positions V = tentV();
    // Corners in face order: 4 0 1 | 4 1 2 | 4 2 3 | 4 3 0 -> distinct positions 4 0 1 2 3.
    Positions expectedV(5, 3);
    for (int i = 0; i < 5; ++i) expectedV.row(i) = V.row(std::vector<int>{4, 0, 1, 2, 3}[i]);
    Faces expectedF(4, 3);
    expectedF << 0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1;
    for (const auto& [name, bytes] :
         std::map<std::string, std::string>{{"tent_ascii.stl", stlAscii(V, toFaces(tentP))},
                                            {"tent_binary.stl", stlBinary(V, toFaces(tentP))}}) {
        SCOPED_TRACE(name);
        const MeshReadResult r = readMesh(writeFile(name, bytes));
        EXPECT_EQ(r.mesh.V, expectedV);
        EXPECT_EQ(r.mesh.F, expectedF);
    }
}

// OpenMesh's readers are process-wide objects that keep the header flags of the last file they
// opened (binary, colours, normals); no read may depend on which file was read before it.
TEST(MeshReaderFormats, EachReadIsIndependentOfTheFileReadBefore) {
    const Positions V = tentV();
    const Faces stlF = (Faces(4, 3) << 0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1).finished();
    Positions stlV(5, 3);
    for (int i = 0; i < 5; ++i) stlV.row(i) = V.row(std::vector<int>{4, 0, 1, 2, 3}[i]);
    std::string coff = "COFF\n5 4 0\n";  // text OFF with vertex and face colours
    for (int i = 0; i < 5; ++i)
        coff += std::to_string(V(i, 0)) + ' ' + std::to_string(V(i, 1)) + ' ' +
                std::to_string(V(i, 2)) + " 0.5 0.5 0.5 1\n";
    for (const auto& f : tentP)
        coff += "3 " + std::to_string(f[0]) + ' ' + std::to_string(f[1]) + ' ' +
                std::to_string(f[2]) + " 255 0 0\n";
    struct File {
        std::string path;
        Positions V;
        Faces F;
    };
    const std::vector<File> files = {
        {writeFile("seq.off", offText(V, tentP)), V, toFaces(tentP)},
        {writeFile("seq_binary.off", offBinary(V, tentP)), V, toFaces(tentP)},
        {writeFile("seq_colour.off", coff), V, toFaces(tentP)},
        {writeFile("seq_ascii.ply", plyAscii(V, tentP)), V, toFaces(tentP)},
        {writeFile("seq_binary.ply", plyBinary(V, tentP)), V, toFaces(tentP)},
        {writeFile("seq_ascii.stl", stlAscii(V, toFaces(tentP))), stlV, stlF},
        {writeFile("seq_binary.stl", stlBinary(V, toFaces(tentP))), stlV, stlF}};
    for (const File& before : files)
        for (const File& file : files) {
            SCOPED_TRACE(fs::path(before.path).filename().string() + " then " +
                         fs::path(file.path).filename().string());
            readMesh(before.path);
            const MeshReadResult r = readMesh(file.path);
            EXPECT_EQ(r.mesh.V, file.V);
            EXPECT_EQ(r.mesh.F, file.F);
        }
}

TEST(MeshReaderFormats, StlTriangleWhoseCornersMergeIsDroppedWithAWarning) {
    Positions V = tentV();
    Faces F(5, 3);
    F << 4, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 0, 0, 1;  // last one repeats a corner position
    const MeshReadResult r = readMesh(writeFile("degenerate.stl", stlBinary(V, F)));
    EXPECT_EQ(r.mesh.faceCount(), 4);
    EXPECT_TRUE(anyWarningContains(r, "1 STL triangle(s) with coinciding corners dropped"));
}

TEST(MeshReaderFormats, ObjSyntaxVariants) {
    const std::string path = writeFile("syntax.obj",
                                       "# comment\n"
                                       "o thing\n"
                                       "v 0 0 0\n"
                                       "v 1 0 0 1.0\n"   // optional w
                                       "v 1 \\\n 1 0\n"  // continued line
                                       "vt 0 0\nvn 0 0 1\n"
                                       "v +0 1 0 # trailing comment\r\n"
                                       "usemtl skin\ns 1\n"
                                       "f 1/1/1 2/1/1 3/1/1\n"
                                       "f -4//1 -2//1 -1//1\n"  // relative: 1 3 4
                                       "curv 0 1 1 2\n");
    const MeshReadResult r = readMesh(path);
    Positions V(4, 3);
    V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
    Faces F(2, 3);
    F << 0, 1, 2, 0, 2, 3;
    EXPECT_EQ(r.mesh.V, V);
    EXPECT_EQ(r.mesh.F, F);
    EXPECT_TRUE(anyWarningContains(r, "'curv'"));
}

// "v +1 0 0" was read but "f +1 2 3" refused, and "v 1 1 1#c" refused for its comment.
TEST(MeshReaderFormats, ObjTakesAPlusSignOnIndicesAndACommentStraightAfterANumber) {
    const MeshReadResult r = readMesh(writeFile(
        "signs.obj", "v 0 0 0#origin\nv +1 0 0\nv 0 1 0 1#w\nvt 0 0#uv\nf +1/+1 2 +3#face\n"));
    Positions V(3, 3);
    V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
    EXPECT_EQ(r.mesh.V, V);
    EXPECT_EQ(r.mesh.F, (Faces(1, 3) << 0, 1, 2).finished());
    EXPECT_EQ(r.warnings, std::vector<std::string>{"open surface: 3 boundary edges in 1 loop"});
    EXPECT_CONTAINS(errorOf(writeFile("plusminus.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf +-1 2 3\n")),
                    "invalid vertex reference '+-1'");
    EXPECT_CONTAINS(errorOf(writeFile("plusminus_v.obj", "v +-1 0 0\n")),
                    "invalid coordinate '+-1'");
}

TEST(MeshReaderFormats, OffWithCommentsAndCountsOnTheKeywordLine) {
    // OpenMesh's OFF reader alone reads garbage counts from both of these.
    const std::string path = writeFile("comments.off",
                                       "# made by hand\nOFF 4 2 0\n0 0 0\n1 0 0 # right\n"
                                       "\n1 1 0\n# between\n0 1 0\n3 0 1 2\n3 0 2 3\n");
    const MeshReadResult r = readMesh(path);
    Faces F(2, 3);
    F << 0, 1, 2, 0, 2, 3;
    EXPECT_EQ(r.mesh.vertexCount(), 4);
    EXPECT_EQ(r.mesh.V.row(2), Eigen::RowVector3d(1, 1, 0));
    EXPECT_EQ(r.mesh.F, F);
}

// A byte-order mark made the first line an unknown keyword: vertex 0 was lost, every later one
// shifted by one, and the mesh read scrambled. Old Mac files (CR alone) read as one line.
TEST(MeshReaderFormats, ObjWithAByteOrderMarkOrOldMacLineEndsReadsEveryVertex) {
    const Positions V = tentV();
    const std::string obj = objText(V, tentP);
    std::string mac = obj;
    std::replace(mac.begin(), mac.end(), '\n', '\r');
    for (const std::string& bytes : {"\xEF\xBB\xBF" + obj, mac, "\xEF\xBB\xBF" + mac}) {
        const MeshReadResult r = readMesh(writeFile("marked.obj", bytes));
        EXPECT_EQ(r.mesh.V, V);
        EXPECT_EQ(r.mesh.F, toFaces(tentP));
        EXPECT_TRUE(r.warnings.size() == 1 && anyWarningContains(r, "open surface"))
            << r.warnings.front();
    }
    // Line numbers count lone CRs too.
    EXPECT_CONTAINS(errorOf(writeFile("mac.obj", "v 0 0 0\rv 1 0 0\r\nv 0 x 0\r")), "(line 3)");
}

// OFF takes the mark; a PLY file must start with "ply", so the refusal names the mark (it said
// "not a PLY file", the culprit invisible).
TEST(MeshReaderFormats, OffWithAByteOrderMarkReadsAndPlyWithOneSaysSo) {
    const Positions V = tentV();
    const MeshReadResult r = readMesh(writeFile("marked.off", "\xEF\xBB\xBF" + offText(V, tentP)));
    EXPECT_EQ(r.mesh.V, V);
    EXPECT_EQ(r.mesh.F, toFaces(tentP));
    for (const std::string& bytes : {plyAscii(V, tentP), plyBinary(V, tentP)})
        EXPECT_CONTAINS(errorOf(writeFile("marked.ply", "\xEF\xBB\xBF" + bytes)),
                        "starts with a UTF-8 byte-order mark");
    EXPECT_CONTAINS(errorOf(writeFile("marked_binary.off", "\xEF\xBB\xBF" + offBinary(V, tentP))),
                    "starts with a UTF-8 byte-order mark");
}

TEST(MeshReaderFormats, ObjKeepsDoublePrecision) {
    const std::string path = writeFile("precise.obj", "v 0.1 0.2 0.3\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const MeshReadResult r = readMesh(path);
    EXPECT_EQ(r.mesh.V(0, 0), 0.1);
    EXPECT_EQ(r.mesh.V(0, 2), 0.3);
}

// ---- Validation errors -----------------------------------------------------------------------

TEST(MeshReaderErrors, MissingFileAndUnknownExtension) {
    for (const std::string name : {"missing.obj", "missing.ply", "missing.stl"}) {
        const std::string path = workPath(name);
        fs::remove(path);
        EXPECT_CONTAINS(errorOf(path), "cannot open the mesh file (");
    }
    const std::string xyz = writeFile("points.xyz", "1 2 3\n");
    EXPECT_CONTAINS(errorOf(xyz), "unknown mesh file extension 'xyz'");
}

TEST(MeshReaderErrors, EmptyMesh) {
    EXPECT_CONTAINS(errorOf(writeFile("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")), "no faces");
    EXPECT_CONTAINS(errorOf(writeFile("empty.off", "OFF\n0 0 0\n")), "no faces");
    EXPECT_CONTAINS(errorOf(writeFile("empty.stl", "solid x\nendsolid x\n")), "no faces");
    // Every face repeats a vertex: nothing left after dropping them.
    EXPECT_CONTAINS(errorOf(writeFile("allbad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 2\n")),
                    "no usable faces");
}

// A binary file named .obj was read as lines of unknown keywords and said "no faces".
TEST(MeshReaderErrors, ABinaryFileNamedObjIsSaidNotToBeText) {
    const std::string blend = std::string("BLENDER-v279REND") + std::string(8, '\0') + "SceneX";
    EXPECT_CONTAINS(errorOf(writeFile("binary.obj", blend)), "is not a text OBJ file: byte 16");
    EXPECT_CONTAINS(errorOf(writeFile("late.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n" +
                                                      std::string(1, '\0') + "f 1 2 3\n")),
                    "byte 24 is a NUL");
}

// An ASCII STL named .obj was read as lines of unknown keywords and said "no faces (nothing to
// animate)"; an OBJ named .stl the same, named .ply "not a PLY file". The first bytes name the
// format the file is in and the extension to give it.
TEST(MeshReaderErrors, AFileInAnotherFormatThanItsExtensionSaysIsNamedAndARenameSuggested) {
    const Positions V = tentV();
    const Faces F = toFaces(tentP);
    const std::vector<std::tuple<std::string, std::string, std::string>> contents = {
        {"obj", objText(V, tentP), "an OBJ file ('v' lines)"},
        {"stl", stlAscii(V, F), "an ASCII STL file ('solid' then 'facet normal' lines)"},
        {"stl", stlBinary(V, F), "a binary STL file (84 + 50 x 4 bytes)"},
        {"ply", plyAscii(V, tentP), "a PLY file (it starts with 'ply')"},
        {"ply", plyBinary(V, tentP), "a PLY file (it starts with 'ply')"},
        {"off", offText(V, tentP), "an OFF file (it starts with 'OFF')"},
        {"off", offBinary(V, tentP), "an OFF file (it starts with 'OFF')"},
        {"off", "\xEF\xBB\xBF# made by hand\n" + offText(V, tentP),
         "an OFF file (it starts with 'OFF')"},
    };
    for (const auto& [format, bytes, looks] : contents)
        for (const std::string ext : {"obj", "stl", "ply", "off"}) {
            if (ext == format) continue;
            std::string upper = ext;
            for (char& c : upper) c = char(std::toupper(static_cast<unsigned char>(c)));
            const std::string msg = errorOf(writeFile("tent." + ext, bytes));
            EXPECT_CONTAINS(msg,
                            "looks like " + looks + ", not " + upper + ": rename it ." + format);
        }
    // An exporter's binary STL header that starts with "solid" is still read as binary.
    const std::string solid = "solid tent" + stlBinary(V, F).substr(10);
    EXPECT_EQ(readMesh(writeFile("solid-header.stl", solid)).mesh.faceCount(), 4);
}

// A cut binary file was parsed as text (its size no longer 84 + 50 n) and reported as having no
// faces; exporters often begin the binary header with "solid" too.
TEST(MeshReaderErrors, ACutBinaryStlIsReportedAsTruncatedWithTheTrianglesItHolds) {
    const std::string whole = stlBinary(tentV(), toFaces(tentP));
    const std::string cut = whole.substr(0, whole.size() * 6 / 10);
    for (const std::string& bytes : {cut, "solid tent" + cut.substr(10)}) {
        const std::string msg = errorOf(writeFile("cut.stl", bytes));
        EXPECT_CONTAINS(msg, "binary STL file is truncated");
        EXPECT_CONTAINS(msg, "the header announces 4 triangles, the file holds 1");
    }
    EXPECT_CONTAINS(errorOf(writeFile("cut.stlb", whole.substr(0, 50))),
                    "50 bytes, shorter than the 84-byte header");
}

// A binary file with a few bytes after its triangles was parsed as text (its size no longer
// 84 + 50 n) and reported as having no faces.
TEST(MeshReaderErrors, ABinaryStlWithBytesAfterItsTrianglesSaysHowMany) {
    const std::string whole = stlBinary(tentV(), toFaces(tentP));
    for (int extra = 1; extra <= 4; ++extra)
        for (const std::string& bytes : {whole, "solid tent" + whole.substr(10)}) {
            const std::string msg =
                errorOf(writeFile("padded.stl", bytes + std::string(size_t(extra), '\0')));
            EXPECT_CONTAINS(msg, "binary STL file has " + std::to_string(extra) +
                                     (extra == 1 ? " byte" : " bytes") +
                                     " more than the 4 triangles its header announces");
            EXPECT_CONTAINS(msg, "84 + 50 x 4 = 284 bytes");
        }
}

TEST(MeshReaderErrors, NonFiniteCoordinates) {
    const std::string obj = writeFile("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
    const std::string msg = errorOf(obj);
    EXPECT_CONTAINS(msg, "non-finite");
    EXPECT_CONTAINS(msg, "vertex 1 (line 2)");

    EXPECT_CONTAINS(errorOf(writeFile("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n")),
                    "vertex 2 (line 3)");

    Positions V = tentV();
    V(2, 1) = std::numeric_limits<double>::quiet_NaN();
    const std::string off = errorOf(writeFile("nan.off", offText(V, tentP)));
    EXPECT_CONTAINS(off, "vertex 2 has a non-finite coordinate");
    EXPECT_CONTAINS(off, "line 6");
    EXPECT_CONTAINS(errorOf(writeFile("nan_ascii.ply", plyAscii(V, tentP))),
                    "vertex 2 has a non-finite");
    const std::string ply = errorOf(writeFile("nan_binary.ply", plyBinary(V, tentP)));
    EXPECT_CONTAINS(ply, "non-finite");
    EXPECT_CONTAINS(ply, "vertex 2");
    EXPECT_CONTAINS(errorOf(writeFile("nan_ascii.stl", stlAscii(V, toFaces(tentP)))), "triangle 1");
    const std::string stl = errorOf(writeFile("nan_binary.stl", stlBinary(V, toFaces(tentP))));
    EXPECT_CONTAINS(stl, "non-finite");
    EXPECT_CONTAINS(stl, "triangle 1");
}

// A corner at 1e300 was read (the solver works in doubles) and written to a glb as infinity, its
// accessor bounds null: invalid glTF. The README's "NaN coordinates are errors" extends to it.
TEST(MeshReaderErrors, CoordinatesBeyondTheRangeOfAFloatAreRefusedWithTheirLine) {
    const std::string obj =
        errorOf(writeFile("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -1e300\nf 1 2 3\n"));
    EXPECT_CONTAINS(obj, "vertex coordinate -1e+300 is beyond the range of a float");
    EXPECT_CONTAINS(obj, "vertex 2 (line 3)");
    EXPECT_CONTAINS(
        errorOf(writeFile("huge_unused.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 4e38 0 0\nf 1 2 3\n")),
        "vertex 3 (line 4)");
    Positions V = tentV();
    V(1, 0) = 1e39;
    EXPECT_CONTAINS(errorOf(writeFile("huge.off", offText(V, tentP))),
                    "vertex coordinate 1e+39 is beyond the range of a float");
    // The largest float itself is fine.
    V(1, 0) = double(std::numeric_limits<float>::max());
    EXPECT_EQ(readMesh(writeFile("largest.off", offText(V, tentP))).mesh.V(1, 0), V(1, 0));
}

TEST(MeshReaderErrors, FaceReferencesMissingVertex) {
    EXPECT_CONTAINS(errorOf(writeFile("relative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n")),
                    "relative index -3 points before the first vertex");
    EXPECT_CONTAINS(errorOf(writeFile("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")),
                    "vertex index 0");
    Polygons P = tentP;
    P[2][1] = 7;
    const std::string off = errorOf(writeFile("range.off", offText(tentV(), P)));
    EXPECT_CONTAINS(off, "face uses vertex 7");
    EXPECT_CONTAINS(off, "face 2");
    EXPECT_CONTAINS(errorOf(writeFile("range.ply", plyBinary(tentV(), P))), "face uses vertex 7");
}

// "f 1 3 9" over three vertices was "face uses vertex 8 but the file has 3 vertices (0-based)
// (face 1 (line 5))": 8 and face 1 were numbers the file does not have (it counts from 1), beside
// its line's. The vertex is named as the face line writes it, at that line; an OFF, which counts
// from 0, keeps its own numbers.
TEST(MeshReaderErrors, AnObjFaceIndexPastTheVerticesIsNamedAsTheFileWritesIt) {
    const std::string obj = writeFile("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 9\n");
    EXPECT_EQ(errorOf(obj), obj +
                                ": face uses vertex 9 but the file has 3 vertices (OBJ indices "
                                "start at 1) (line 5)");
    const std::string group =
        writeFile("range-group.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\ng a\nf 1 2 3\ng b\nf 3 2 4\n");
    MeshReadOptions b;
    b.group = "b";
    EXPECT_EQ(errorOf(group, [&] { readMesh(group, b); }),
              group +
                  ": face uses vertex 4 but the file has 3 vertices (OBJ indices start at 1) "
                  "(line 7)");
    Polygons P = tentP;
    P[2][1] = 7;
    const std::string off = writeFile("range-own.off", offText(tentV(), P));
    EXPECT_CONTAINS(errorOf(off), "face uses vertex 7 but the file has 5 vertices (0-based)");
}

TEST(MeshReaderErrors, MalformedTextThatOpenMeshWouldAccept) {
    // OpenMesh's OFF reader reads "x" as 0 and runs past the end of a short file.
    std::string off = offText(tentV(), tentP);
    off.replace(off.rfind("4 3 0"), 5, "4 3 x");
    EXPECT_CONTAINS(errorOf(writeFile("token.off", off)), "'x' is not a vertex index");
    EXPECT_CONTAINS(errorOf(writeFile("keyword.off", "OFF4OFF\n3 1513333333\n")),
                    "not an OFF file: first word is 'OFF4OFF'");
    EXPECT_CONTAINS(errorOf(writeFile("short.off", "OFF\n5 4 0\n1 0 0\n0 1 0\n")),
                    "file ends after 2 of 5 vertices");
    EXPECT_CONTAINS(
        errorOf(writeFile("short.ply", plyHeader("ascii", 5, 1) + "1 0 0 200\n0 1 0 200\n")),
        "file ends in vertex 2");
    EXPECT_CONTAINS(
        errorOf(writeFile("huge.ply", plyHeader("binary_little_endian", 2000000000, 1) + "xx")),
        "header announces 2000000000 vertex elements, more than the file holds");
    EXPECT_CONTAINS(errorOf(writeFile("bad.obj", "v 0 zero 0\n")), "invalid coordinate 'zero'");
    EXPECT_CONTAINS(errorOf(writeFile("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n")),
                    "face with 2 corner(s)");
    EXPECT_CONTAINS(
        errorOf(writeFile("nope.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n")),
        "expected 'vertex x y z'");
    // Found by fuzzing: a line holding only a vertical tab or a form feed has no first word.
    const std::string tabbed = "solid x\n\v\n" + stlAscii(tentV(), toFaces(tentP)).substr(11);
    EXPECT_EQ(readMesh(writeFile("vtab.stl", tabbed)).mesh.F.rows(), toFaces(tentP).rows());
    EXPECT_CONTAINS(errorOf(writeFile("formfeed.off", "\f\n\f\nfil")), "fil");
}

// A header counting one face too few dropped the last face silently (OpenMesh stops reading at
// the count): ascii and binary PLY, text and binary OFF.
TEST(MeshReaderErrors, DataAfterTheElementsTheHeaderAnnouncesIsRefused) {
    const Positions V = tentV();
    const Polygons three(tentP.begin(), tentP.begin() + 3);
    const auto undercount = [](std::string bytes, const std::string& from, const std::string& to) {
        return bytes.replace(bytes.find(from), from.size(), to);
    };
    const std::string ascii =
        errorOf(writeFile("extra.ply", undercount(plyAscii(V, tentP), "face 4", "face 3")));
    EXPECT_CONTAINS(ascii, "more data than the header announces (5 vertex, 3 face)");
    EXPECT_CONTAINS(ascii, "'3' follows the last element (line 20)");
    const std::string binary =
        errorOf(writeFile("extra_binary.ply", undercount(plyBinary(V, tentP), "face 4", "face 3")));
    EXPECT_CONTAINS(binary, "13 bytes follow the elements the header announces (5 vertex, 3 face)");
    const std::string off =
        errorOf(writeFile("extra.off", undercount(offText(V, tentP), "5 4 0", "5 3 0")));
    EXPECT_CONTAINS(off, "more lines than the header announces (5 vertices, 3 faces)");
    EXPECT_CONTAINS(off, "(line 12)");
    std::string offBytes = offBinary(V, tentP);
    offBytes[15] = 3;  // the face count
    EXPECT_CONTAINS(errorOf(writeFile("extra_binary.off", offBytes)),
                    "16 bytes follow the 3 faces the header announces");

    // What is no data is not refused: an element after the faces, comments and blank lines at the
    // end of an ascii file, a newline after a binary one.
    std::string edges = plyAscii(V, three);
    edges.replace(edges.find("end_header"), 10,
                  "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header");
    edges += "0 1\n\ncomment written by hand\n  \n";
    EXPECT_EQ(readMesh(writeFile("edges.ply", edges)).mesh.faceCount(), 3);
    EXPECT_CONTAINS(errorOf(writeFile("edges2.ply", edges + "2 3\n")),
                    "'2' follows the last element");
    EXPECT_EQ(readMesh(writeFile("newline.ply", plyBinary(V, three) + "\n")).mesh.faceCount(), 3);
    EXPECT_EQ(readMesh(writeFile("comment.off", offText(V, three) + "# end\n\n")).mesh.faceCount(),
              3);
}

// A header counting one vertex too few made the last vertex face 0: "face 0: '-0.12' is not an
// integer", and OFF "-8 6 0" "face 0 lists fewer than 3 corners"; neither named the header.
TEST(MeshReaderErrors, AWrongVertexCountInTheHeaderIsNamedAsTheLikelyCause) {
    Positions V = tentV();
    V(4, 0) = 0.25;
    std::string ply = plyAscii(V, tentP);
    ply.replace(ply.find("vertex 5"), 8, "vertex 4");
    const std::string short_ = errorOf(writeFile("short_count.ply", ply));
    EXPECT_CONTAINS(short_,
                    "face 0: '0.25' is not an integer: is the header's count of vertex "
                    "elements (4) too small? (line 16)");
    ply.replace(ply.find("vertex 4"), 8, "vertex 6");
    EXPECT_CONTAINS(errorOf(writeFile("long_count.ply", ply)),
                    "file ends in face 3 (the header announces 6 vertex, 4 face)");

    std::string off = offText(V, tentP);
    off.replace(off.find("5 4 0"), 5, "4 4 0");
    EXPECT_CONTAINS(errorOf(writeFile("short_count.off", off)),
                    "face 0: bad corner count '0.25': is the header's vertex count (4) too small?");
    off.replace(off.find("4 4 0"), 5, "-8 4 0");
    EXPECT_CONTAINS(errorOf(writeFile("negative.off", off)),
                    "OFF header: the vertex count -8 is negative (line 3)");
}

// Found by fuzzing: OpenMesh read a corner count of 2^32-1 as that many stale indices.
TEST(MeshReaderErrors, BinaryOffCountsTheFileCannotHold) {
    const std::string good = offBinary(tentV(), tentP);
    const size_t faces = good.size() - 4 * 16;  // the first face's corner count
    std::string corners = good;
    corners.replace(faces, 4, std::string(4, '\xff'));
    EXPECT_CONTAINS(errorOf(writeFile("corners.off", corners)),
                    "face 0 announces 4294967295 corners, more than the file holds");
    std::string vertices = good;
    vertices[11] = '\x7f';  // vertex count 127
    EXPECT_CONTAINS(errorOf(writeFile("vertices.off", vertices)),
                    "header announces 127 vertices, more than the file holds");
    EXPECT_CONTAINS(errorOf(writeFile("cut.off", good.substr(0, good.size() - 2))),
                    "face 3 announces 3 corners, more than the file holds");
    EXPECT_CONTAINS(errorOf(writeFile("cut2.off", good.substr(0, good.size() - 14))),
                    "binary OFF file ends in face 3");
}

// Found by fuzzing: "BINARY" further along the first line is text OFF to OpenMesh, whose text
// parser took a binary corner count as a face of billions of corners.
TEST(MeshReaderErrors, BinaryWordOpenMeshDoesNotSeeIsReadAsText) {
    std::string spaced = offBinary(tentV(), tentP);
    spaced.replace(0, 10, "OFF \f\fBINARY");
    EXPECT_CONTAINS(errorOf(writeFile("spaced.off", spaced)),
                    "OFF header lacks the vertex and face counts");
    std::string tab = offBinary(tentV(), tentP);
    tab[3] = '\t';  // one character of any kind: still binary
    EXPECT_EQ(readMesh(writeFile("tab.off", tab)).mesh.faceCount(), 4);
}

// Found by fuzzing: OpenMesh's PLY header parser loops for ever on a count it cannot read.
TEST(MeshReaderErrors, PlyHeaderThatOpenMeshWouldNeverFinish) {
    const std::string good = plyAscii(tentV(), tentP);
    std::string count = good;
    count.replace(count.find("vertex 5"), 8, "vertex ]");
    EXPECT_CONTAINS(errorOf(writeFile("count.ply", count)), "element vertex has no count (']')");
    std::string version = good;
    version.replace(version.find("1.0"), 3, "x");
    EXPECT_CONTAINS(errorOf(writeFile("version.ply", version)), "version 'x' is not a number");
    // Found by fuzzing in CI: a version of dots alone, and a line that is not "format".
    std::string dot = good;
    dot.replace(dot.find("1.0"), 3, ".");
    EXPECT_CONTAINS(errorOf(writeFile("dot.ply", dot)), "version '.' is not a number");
    std::string huge = good;
    huge.replace(huge.find("1.0"), 3, std::string(50, '7'));
    EXPECT_CONTAINS(errorOf(writeFile("huge.ply", huge)), "is not a number");
    std::string formatLine = good;
    formatLine.replace(formatLine.find("format"), 6, "t");
    EXPECT_CONTAINS(errorOf(writeFile("t.ply", formatLine)), "no format line after 'ply'");
    std::string end = good;
    end.replace(end.find("end_header"), 10, "xend_header");
    EXPECT_CONTAINS(errorOf(writeFile("end.ply", end)), "PLY header has no end_header");
    EXPECT_CONTAINS(
        errorOf(writeFile("property.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n")),
        "a property before any element");
}

// Found by fuzzing: OpenMesh reads a list length the file cannot hold as that many values.
TEST(MeshReaderErrors, PlyListLongerThanTheFile) {
    std::string binary = plyBinary(tentV(), tentP);
    binary.replace(binary.find("list uchar int"), 14, "list int int");
    const size_t faces = binary.size() - 4 * 13;
    std::string body = binary.substr(0, faces);
    for (const auto& f : tentP) {
        put(body, int32_t(f.size()));
        for (int v : f) put(body, int32_t(v));
    }
    EXPECT_EQ(readMesh(writeFile("list.ply", body)).mesh.F, toFaces(tentP));
    body.replace(faces, 4, "\xff\xff\xff\x7f");
    EXPECT_CONTAINS(errorOf(writeFile("long.ply", body)),
                    "face 0 lists more values than the file holds");
    std::string ascii = plyAscii(tentV(), tentP);
    ascii.replace(ascii.rfind("\n3 "), 3, "\n9 ");
    EXPECT_CONTAINS(errorOf(writeFile("long_ascii.ply", ascii)),
                    "face 3: list length '9' is more than the file holds");
    // OpenMesh reads words, not lines: a list that runs on into the next line is its business,
    // a word it cannot read is not (found by fuzzing: its loops then run on stale counts).
    std::string word = plyAscii(tentV(), tentP);
    word.replace(word.rfind("\n3 "), 3, "\n3J ");
    EXPECT_CONTAINS(errorOf(writeFile("word.ply", word)), "face 3: '3J' is not a number");
}

// A format word that is none of the three was read as binary ("file ends in face 1422" of
// "format asci"); it is named, and nothing reaches the console.
TEST(MeshReaderErrors, APlyFormatThatIsNoneOfTheThreeIsNamed) {
    for (const char* format : {"binary_middle_endian", "asci"}) {
        std::string bytes = plyAscii(tentV(), tentP);
        bytes.replace(bytes.find("ascii"), 5, format);
        const std::string path = writeFile("format.ply", bytes);
        ::testing::internal::CaptureStderr();
        const std::string msg = errorOf(path);
        EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
        EXPECT_CONTAINS(msg, "PLY header: format '" + std::string(format) +
                                 "' is none of ascii, binary_little_endian, binary_big_endian");
    }
}

// "obj_info" is a standard PLY header line, not worth a note; a word no PLY header holds is.
TEST(MeshReaderWarnings, AnUnknownPlyHeaderLineIsANoteAndObjInfoIsNone) {
    std::string ply = plyAscii(tentV(), tentP);
    ply.insert(ply.find("element"), "obj_info scanned 2026\nfoo bar\n");
    const MeshReadResult r = readMesh(writeFile("obj_info.ply", ply));
    EXPECT_EQ(r.mesh.F, toFaces(tentP));
    EXPECT_EQ(r.warnings,
              (std::vector<std::string>{"PLY header: 'foo' is no PLY keyword; its line skipped",
                                        "open surface: 4 boundary edges in 1 loop"}));
}

// Valid files OpenMesh misread, from a user's probe (2 December 2026): MeshLab's per-face texture
// coordinates ("face 1056964608" was 0.5 read as an index, or "face with 0 corners"), integer
// coordinates in binary (10,278 console lines, then a nonsense vertex index), and a comment that
// says "end_header" (the body was taken to start there).
TEST(MeshReaderFormats, PlyWithFacePropertiesIntegerCoordinatesAndEitherByteOrderReads) {
    const Positions V = 2.0 * tentV();  // whole numbers, for the integer coordinates
    const auto header = [&](const char* format, const char* coordinate, const char* faceFirst,
                            const char* faceAfter) {
        return std::string("ply\nformat ") + format +
               " 1.0\ncomment end_header is a word like any\nelement vertex " +
               std::to_string(V.rows()) + "\nproperty " + coordinate + " x\nproperty " +
               coordinate + " y\nproperty " + coordinate + " z\nproperty float nx\nelement face " +
               std::to_string(tentP.size()) + "\n" + faceFirst +
               "property list uchar uint vertex_indices\n" + faceAfter + "end_header\n";
    };
    const char* texcoords = "property list uchar float texcoord\n";
    const char* flags = "property uchar flags\n";
    // Little and big endian, short and float coordinates, a list and a value before and after.
    for (const bool big : {false, true})
        for (const bool shorts : {false, true}) {
            std::string s = header(big ? "binary_big_endian" : "binary_little_endian",
                                   shorts ? "short" : "float", flags, texcoords);
            const auto bytes = [&](const void* p, size_t n) {
                const char* c = static_cast<const char*>(p);
                for (size_t k = 0; k < n; ++k) s += c[big ? n - 1 - k : k];
            };
            for (int i = 0; i < V.rows(); ++i) {
                for (int k = 0; k < 3; ++k) {
                    const float f = float(V(i, k));
                    const int16_t h = int16_t(V(i, k));
                    shorts ? bytes(&h, 2) : bytes(&f, 4);
                }
                const float normal = 1;
                bytes(&normal, 4);
            }
            for (const auto& f : tentP) {
                s += char(7);  // flags
                s += char(f.size());
                for (int v : f) {
                    const uint32_t u = uint32_t(v);
                    bytes(&u, 4);
                }
                s += char(2 * f.size());
                for (size_t k = 0; k < 2 * f.size(); ++k) {
                    const float uv = 0.5f;
                    bytes(&uv, 4);
                }
            }
            const MeshReadResult r = readMesh(writeFile("meshlab.ply", s));
            EXPECT_EQ(r.mesh.V, V) << big << shorts;
            EXPECT_EQ(r.mesh.F, toFaces(tentP)) << big << shorts;
        }
    std::ostringstream ascii;
    ascii << header("ascii", "int", texcoords, flags);
    for (int i = 0; i < V.rows(); ++i)
        ascii << int(V(i, 0)) << ' ' << int(V(i, 1)) << ' ' << int(V(i, 2)) << " 1\n";
    for (const auto& f : tentP) {
        ascii << 2 * f.size();
        for (size_t k = 0; k < 2 * f.size(); ++k) ascii << " 0.5";
        ascii << ' ' << f.size();
        for (int v : f) ascii << ' ' << v;
        ascii << " 7\n";
    }
    const MeshReadResult r = readMesh(writeFile("meshlab_ascii.ply", ascii.str()));
    EXPECT_EQ(r.mesh.V, V);
    EXPECT_EQ(r.mesh.F, toFaces(tentP));

    // Double coordinates keep their precision (OpenMesh rounded them to float).
    std::string precise = plyAscii(V, tentP);
    const std::string floats = "float x\nproperty float y\nproperty float z", first = "\n2 0 0 200";
    precise.replace(precise.find(floats), floats.size(),
                    "double x\nproperty double y\nproperty double z");
    precise.replace(precise.find(first), first.size(), "\n2.1234567890123 0 0 200");
    EXPECT_EQ(readMesh(writeFile("double.ply", precise)).mesh.V(0, 0), 2.1234567890123);
}

// From a review of the reader (2 December 2026): elements without properties take no data (walking
// their counts made reading quadratic), a list length is read in its own (signed) type, the
// standard's vertex_indices wins over vertex_index, a normal may be nan in ascii as in binary, and
// a header that names a vertex or face element twice, or a property twice, is refused.
TEST(MeshReaderFormats, PlyElementsWithoutPropertiesSignedLengthsAndRepeatedNames) {
    const Positions V = tentV();
    std::string empty = plyAscii(V, tentP);
    empty.insert(empty.find("element vertex"), "element nothing 1000000\n");
    EXPECT_EQ(readMesh(writeFile("empty_elements.ply", empty)).mesh.F, toFaces(tentP));

    std::string both = plyAscii(V, tentP);
    both.replace(both.find("property list uchar int vertex_indices"), 38,
                 "property list uchar int vertex_index\nproperty list uchar int vertex_indices");
    std::string body = both.substr(0, both.find("end_header\n") + 11);
    std::istringstream lines(both.substr(body.size()));
    std::string line;
    for (int i = 0; i < V.rows() && std::getline(lines, line);) body += line + "\n", ++i;
    for (const auto& f : tentP)  // vertex_index: a wrong triangle; vertex_indices: the face
        body += "3 0 1 2 3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " +
                std::to_string(f[2]) + "\n";
    EXPECT_EQ(readMesh(writeFile("both_lists.ply", body)).mesh.F, toFaces(tentP));

    std::string normals = plyAscii(V, tentP);
    normals.replace(normals.find("property uchar red"), 18, "property float nx");
    normals.replace(normals.find(" 200\n"), 5, " nan\n");
    EXPECT_EQ(readMesh(writeFile("nan_normal.ply", normals)).mesh.V, V);

    std::string negative = plyAscii(V, tentP);
    negative.replace(negative.rfind("\n3 "), 3, "\n-1 ");
    EXPECT_CONTAINS(errorOf(writeFile("negative.ply", negative)),
                    "face 3: list length '-1' is negative");
    std::string signedBinary = plyBinary(V, tentP);
    signedBinary.replace(signedBinary.find("list uchar int"), 14, "list char int");
    signedBinary[signedBinary.size() - 13] = char(0xFF);  // the last face's corner count
    EXPECT_CONTAINS(errorOf(writeFile("negative_binary.ply", signedBinary)),
                    "face 3: list length -1 is negative");

    std::string twice = plyAscii(V, tentP);
    twice.insert(twice.find("end_header"), "element face 0\n");
    EXPECT_CONTAINS(errorOf(writeFile("two_faces.ply", twice)),
                    "PLY header: a second element face");
    std::string twoX = plyAscii(V, tentP);
    twoX.replace(twoX.find("property uchar red"), 18, "property float x");
    EXPECT_CONTAINS(errorOf(writeFile("two_x.ply", twoX)),
                    "PLY header: element vertex has two properties x");

    std::string cut = plyBinary(V, tentP);
    cut.resize(cut.find("end_header\n") + 11 + 2 * 13 + 6);  // in vertex 2
    EXPECT_CONTAINS(errorOf(writeFile("cut.ply", cut)), "file ends in vertex 2");
    std::string extra = plyAscii(V, tentP);
    extra.replace(extra.find("property uchar red"), 18, "property uchar red  # colour");
    for (const std::string& w : readMesh(writeFile("extra_words.ply", extra)).warnings)
        EXPECT_EQ(w.find("PLY header"), std::string::npos) << w;
}

// What a PLY file must hold to be a mesh, said of the header.
TEST(MeshReaderErrors, APlyWithoutCoordinatesOrIntegerIndicesSaysWhatItLacks) {
    std::string noZ = plyAscii(tentV(), tentP);
    noZ.replace(noZ.find("property float z"), 16, "property float w");
    EXPECT_CONTAINS(errorOf(writeFile("no_z.ply", noZ)),
                    "PLY header: element vertex lacks an x, y or z property");
    std::string noIndices = plyAscii(tentV(), tentP);
    noIndices.replace(noIndices.find("vertex_indices"), 14, "corners");
    EXPECT_CONTAINS(errorOf(writeFile("no_indices.ply", noIndices)),
                    "PLY header: element face has no vertex_indices list");
    std::string floats = plyAscii(tentV(), tentP);
    floats.replace(floats.find("list uchar int"), 14, "list uchar float");
    EXPECT_CONTAINS(errorOf(writeFile("float_indices.ply", floats)),
                    "PLY header: face vertex indices of type 'float', not integers");
}

TEST(MeshReaderErrors, EdgeSharedByThreeFaces) {
    const std::string path = writeFile("fin.obj",
                                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                                       "f 1 2 3\nf 2 1 4\nf 1 2 5\n");
    const std::string msg = errorOf(path);
    EXPECT_CONTAINS(msg, "non-manifold edge 0-1: shared by 3 faces");
    EXPECT_CONTAINS(msg, "face 2 (line 8)");
}

TEST(MeshReaderErrors, TwoFacesUsingTheSameDirectedEdge) {
    // Second triangle runs 0->1 like the first: one of them is flipped.
    const std::string path =
        writeFile("flip.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nf 1 2 3\nf 1 2 4\n");
    const std::string msg = errorOf(path);
    EXPECT_CONTAINS(msg, "inconsistent orientation");
    EXPECT_CONTAINS(msg, "edge 0->1");
    EXPECT_CONTAINS(msg, "face 0 (line 5) and face 1 (line 6)");
}

TEST(MeshReaderErrors, VertexWhereTwoFansMeet) {
    // Two triangles touching only at vertex 2 (a bow tie), then a valid third one elsewhere.
    const std::string path = writeFile("bowtie.off",
                                       "OFF\n5 2 0\n-1 -1 0\n-1 1 0\n0 0 0\n1 -1 0\n1 1 0\n"
                                       "3 0 2 1\n3 2 3 4\n");
    const std::string msg = errorOf(path);
    EXPECT_CONTAINS(msg, "non-manifold vertex 2: its faces form 2 separate fans");
    // Same through OBJ, where the vertex line is known.
    const std::string obj = errorOf(writeFile("bowtie.obj",
                                              "v -1 -1 0\nv -1 1 0\nv 0 0 0\nv 1 -1 0\nv 1 1 0\n"
                                              "f 1 3 2\nf 3 4 5\n"));
    EXPECT_CONTAINS(obj, "vertex 2 (line 3)");
}

TEST(MeshReaderErrors, GroupOnlyForObjAndMustExist) {
    const std::string ply = writeFile("tent_group.ply", plyAscii(tentV(), tentP));
    EXPECT_CONTAINS(errorOf(ply, [&] { readMesh(ply, {"body"}); }), "only OBJ files have groups");
    const std::string obj =
        writeFile("groups_missing.obj", "g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\ng b\n");
    const std::string msg = errorOf(obj, [&] { readMesh(obj, {"body"}); });
    EXPECT_CONTAINS(msg, "no group named 'body'");
    EXPECT_CONTAINS(msg, "groups: a, b");
    EXPECT_CONTAINS(errorOf(obj, [&] { readMesh(obj, {"b"}); }), "group 'b' has no usable faces");
}

// ---- Accepted with warnings ------------------------------------------------------------------

TEST(MeshReaderWarnings, OpenSurfaceReportsBoundaryLoops) {
    const MeshReadResult r = readMesh(writeFile("tent_open.obj", objText(tentV(), tentP)));
    EXPECT_EQ(r.boundaryEdges, 4);
    EXPECT_EQ(r.boundaryLoops, 1);
    EXPECT_EQ(r.components, 1);
    EXPECT_TRUE(anyWarningContains(r, "4 boundary edges in 1 loop"));
}

TEST(MeshReaderWarnings, ClosedSurfaceHasNoWarnings) {
    Positions V(4, 3);
    V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
    const MeshReadResult r = readMesh(
        writeFile("tetra.ply", plyBinary(V, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}})));
    EXPECT_EQ(r.boundaryEdges, 0);
    EXPECT_EQ(r.components, 1);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
}

TEST(MeshReaderWarnings, SeveralComponentsIsolatedVerticesZeroAreaAndRepeatedCorners) {
    const std::string path = writeFile("mixed.obj",
                                       "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                       "v 9 9 9\n"  // isolated, between the components
                                       "v 5 0 0\nv 6 0 0\nv 7 0 0\n"  // collinear: zero area
                                       "f 1 2 3\n"
                                       "f 5 6 7\n"
                                       "f 1 2 2\n");  // repeated corner: dropped
    const MeshReadResult r = readMesh(path);
    EXPECT_EQ(r.mesh.vertexCount(), 7);
    EXPECT_EQ(r.mesh.V.row(3), Eigen::RowVector3d(9, 9, 9));  // kept in place
    EXPECT_EQ(r.mesh.faceCount(), 2);
    EXPECT_EQ(r.components, 2);
    EXPECT_EQ(r.isolatedVertices, 1);
    EXPECT_EQ(r.zeroAreaFaces, 1);
    EXPECT_EQ(r.droppedFaces, 1);
    EXPECT_TRUE(anyWarningContains(r, "2 connected components"));
    EXPECT_TRUE(anyWarningContains(r, "1 isolated vertex (kept, used by no face): 3"));
    EXPECT_TRUE(anyWarningContains(r, "1 zero-area triangle, from face 1 (line 9)"));
    EXPECT_TRUE(anyWarningContains(r, "dropped 1 face with a repeated vertex: face 2 (line 10)"));
}

// One unused vertex far away set the scale of "no area": every triangle of the mesh was
// reported zero-area (and the solver's tolerances grew with it). A polygon split into several
// flat triangles was listed once per triangle.
TEST(MeshReaderWarnings, ZeroAreaIsJudgedByTheVerticesFacesUseAndListsEachPolygonOnce) {
    const MeshReadResult far =
        readMesh(writeFile("far.obj", objText(tentV(), tentP) + "v 1e7 0 0\n"));
    EXPECT_EQ(far.isolatedVertices, 1);
    EXPECT_EQ(far.zeroAreaFaces, 0);
    EXPECT_FALSE(anyWarningContains(far, "zero-area"));

    const MeshReadResult flat = readMesh(writeFile("flat.obj",
                                                   "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nv 0 1 0\n"
                                                   "f 1 2 3 4\nf 1 4 5\n"));
    EXPECT_EQ(flat.zeroAreaFaces, 2);
    EXPECT_EQ(flat.warnings.back(), "2 zero-area triangles, from face 0 (line 6)");
}

// ---- Triangulation ---------------------------------------------------------------------------

namespace {

// Signed area of triangle t along +z, for meshes in the z = 0 plane.
double areaZ(const TriMesh& m, int t) {
    const Eigen::Vector3d a = m.V.row(m.F(t, 0)), b = m.V.row(m.F(t, 1)), c = m.V.row(m.F(t, 2));
    return 0.5 * (b - a).cross(c - a).z();
}

bool usesEdge(const TriMesh& m, int a, int b) {
    for (int t = 0; t < m.faceCount(); ++t)
        for (int k = 0; k < 3; ++k)
            if (std::minmax(m.F(t, k), m.F(t, (k + 1) % 3)) == std::minmax(a, b)) return true;
    return false;
}

MeshReadResult readPolygon(const std::string& name, const Positions& V,
                           const std::vector<int>& polygon) {
    return readMesh(writeFile(name, objText(V, {polygon})));
}

}  // namespace

TEST(MeshReaderTriangulation, ConvexQuadTakesTheShorterDiagonalWhereverItStarts) {
    Positions V(4, 3);
    V << 0, 0, 0, 4, 0, 0, 5, 1, 0, 0, 1, 0;  // diagonal 1-3 is shorter than 0-2
    for (const auto& quad : {std::vector<int>{0, 1, 2, 3}, {1, 2, 3, 0}}) {
        const MeshReadResult r = readPolygon("quad.obj", V, quad);
        EXPECT_EQ(r.polygonsTriangulated, 1);
        ASSERT_EQ(r.mesh.faceCount(), 2);
        EXPECT_TRUE(usesEdge(r.mesh, 1, 3));
        EXPECT_FALSE(usesEdge(r.mesh, 0, 2));
        EXPECT_EQ(r.sourceFaceIndex, (std::vector<int>{0, 0}));
    }
}

TEST(MeshReaderTriangulation, DartQuadAvoidsTheShorterButOutsideDiagonal) {
    Positions V(4, 3);
    V << -1, 0, 0, 0, 10, 0, 1, 0, 0, 0, 0.1, 0;  // reflex at vertex 3; 0-2 is short but outside
    const MeshReadResult r = readPolygon("dart.obj", V, {0, 3, 2, 1});
    ASSERT_EQ(r.mesh.faceCount(), 2);
    EXPECT_TRUE(usesEdge(r.mesh, 1, 3));
    for (int t = 0; t < 2; ++t) EXPECT_GT(areaZ(r.mesh, t), 0.0);  // no fold-over
}

TEST(MeshReaderTriangulation, NonConvexHexagonCoversItsAreaWithoutFolds) {
    Positions V(6, 3);  // an L shape, counter-clockwise, area 3
    V << 0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0;
    for (int start = 0; start < 6; ++start) {
        std::vector<int> polygon;
        for (int i = 0; i < 6; ++i) polygon.push_back((start + i) % 6);
        const MeshReadResult r = readPolygon("ell.obj", V, polygon);
        ASSERT_EQ(r.mesh.faceCount(), 4);
        double area = 0;
        for (int t = 0; t < 4; ++t) {
            EXPECT_GT(areaZ(r.mesh, t), 0.0) << "start " << start << " triangle " << t;
            area += areaZ(r.mesh, t);
        }
        EXPECT_NEAR(area, 3.0, 1e-12);
    }
}

// Two hexagons across a crease, sharing the path P-Q-R (as a MakeHuman n-gon mesh's 590 589 572
// 573 574 591 and 607 606 589 590 591 608): both once cut their ear at Q, each adding the
// diagonal P-R, which four triangles then shared ("non-manifold edge").
TEST(MeshReaderTriangulation, TwoHexagonsSharingTwoSidesDoNotBothCutTheSameDiagonal) {
    Positions V(9, 3);
    V << 0, 0.3, -0.3,                                         // Q, bulging out of both
        -1, 0, 0, -1.5, -3, 0, 0, -4, 0, 1.5, -3, 0, 1, 0, 0,  // P, A's own three, R
        0, 0, 4, -1.5, 0, 3, 1.5, 0, 3;                        // B's own three
    const MeshReadResult r =
        readMesh(writeFile("hexagons.obj", objText(V, {{0, 1, 2, 3, 4, 5}, {6, 7, 1, 0, 5, 8}})));
    EXPECT_EQ(r.polygonsTriangulated, 2);
    ASSERT_EQ(r.mesh.faceCount(), 8);
    int usingPR = 0;
    for (int t = 0; t < 8; ++t)
        for (int k = 0; k < 3; ++k)
            usingPR += std::minmax(r.mesh.F(t, k), r.mesh.F(t, (k + 1) % 3)) == std::minmax(1, 5);
    EXPECT_EQ(usingPR, 2);
}

// A quad whose both diagonals are edges of the file's other faces cannot be split without
// repeating one: the message says the split made the edge, which no face of the file has twice.
TEST(MeshReaderTriangulation, AnEdgeOnlyTheSplitCouldRepeatIsSaidToBeTheSplits) {
    Positions V(6, 3);
    V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1, 0.5, 0.5, -1;
    const std::string path =
        writeFile("forced.obj", objText(V, {{0, 1, 2, 3}, {0, 2, 4}, {1, 3, 5}}));
    EXPECT_CONTAINS(errorOf(path), "Boneless made it splitting the file's polygons into triangles");
}

// ---- OBJ groups ------------------------------------------------------------------------------

TEST(MeshReaderGroups, SelectedGroupKeepsItsVerticesInFileOrder) {
    const std::string path = writeFile("groups.obj",
                                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 0 0\nv 2 1 0\n"
                                       "g left\nf 1 2 3\nf 2 4 3\n"
                                       "g right shared\nf 2 5 6\nf -5 6 4\n"
                                       "o lonely\ng\nf 1 2 3\n");  // bare "g": back to no group
    const std::vector<ObjGroup> groups = objGroups(path);
    std::vector<std::string> names;
    for (const ObjGroup& g : groups) names.push_back(g.name);
    EXPECT_EQ(names, (std::vector<std::string>{"left", "right", "shared", "lonely"}));
    // Each group's size is the vertex count of the mesh read for it.
    for (const ObjGroup& g : groups)
        EXPECT_EQ(g.vertices, readMesh(path, {g.name}).mesh.vertexCount()) << g.name;
    EXPECT_EQ(groups[0].vertices, 4);
    EXPECT_EQ(groups[3].vertices, 3);

    const MeshReadResult r = readMesh(path, {"right"});
    EXPECT_EQ(r.sourceVertexCount, 6);
    EXPECT_EQ(r.sourceVertexIndex, (std::vector<int>{1, 3, 4, 5}));
    Faces F(2, 3);
    F << 0, 2, 3, 0, 3, 1;  // file faces (1 4 5) and (1 5 3) remapped
    EXPECT_EQ(r.mesh.F, F);
    EXPECT_EQ(r.mesh.V.row(1), Eigen::RowVector3d(1, 1, 0));
    EXPECT_EQ(r.sourceFaceCount, 2);
    EXPECT_EQ(r.sourceFaceIndex, (std::vector<int>{2, 3}));  // numbered among all the file's faces
    // Messages name file faces and lines too.
    const std::string bad = writeFile(
        "groups_bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nf 1 2 3\ng g\nf 1 2 3\nf 1 2 4\n");
    EXPECT_CONTAINS(errorOf(bad, [&] { readMesh(bad, {"g"}); }),
                    "face 1 (line 7) and face 2 (line 8)");

    // A second name on the same "g" line selects the same faces; "o" names work too.
    EXPECT_EQ(readMesh(path, {"shared"}).mesh.F, F);
    EXPECT_EQ(readMesh(path, {"lonely"}).sourceVertexIndex, (std::vector<int>{0, 1, 2}));
}

// The OBJ fuzzer's find: a comment straight after a corner's slash ("3/1/#1") ends the face
// there, so the face is a triangle; the group chooser counted the fourth corner after it.
TEST(MeshReaderGroups, AGroupsVertexCountIsTheReadMeshsWhenACommentCutsAFace) {
    const std::string path = writeFile(
        "cut-face.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ng quad\nf 1/1/1 2/1/1 3/1/#1 4/1/1\n");
    const std::vector<ObjGroup> groups = objGroups(path);
    ASSERT_EQ(groups.size(), 1u);
    EXPECT_EQ(groups[0].vertices, readMesh(path, {"quad"}).mesh.vertexCount());
    EXPECT_EQ(groups[0].vertices, 3);
}

TEST(MeshReaderGroups, NonObjFilesHaveNoGroups) {
    EXPECT_TRUE(objGroups(writeFile("nogroups.off", offText(tentV(), tentP))).empty());
    EXPECT_TRUE(objGroups(writeFile("nogroups.obj", objText(tentV(), tentP))).empty());
}

// ---- Real data (skipped without ../shared/data) ----------------------------------------------

TEST(MeshReaderRealData, MakeHumanWholeFileAndBodyGroup) {
    const std::string path = dataPath("meshes/makehuman/makehuman_base.obj");
    if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
    const auto groups = objGroups(path);
    ASSERT_FALSE(groups.empty());
    EXPECT_EQ(groups.front().name, "body");
    EXPECT_EQ(groups.front().vertices, 13380);

    const MeshReadResult all = readMesh(path);
    EXPECT_EQ(all.mesh.vertexCount(), 19158);
    EXPECT_EQ(all.sourceFaceCount, 18486);
    EXPECT_EQ(all.polygonsTriangulated, 18486);  // all quads
    EXPECT_EQ(all.mesh.faceCount(), 2 * 18486);

    const MeshReadResult body = readMesh(path, {"body"});
    EXPECT_EQ(body.mesh.vertexCount(), 13380);
    EXPECT_EQ(body.sourceFaceCount, 13378);
    EXPECT_EQ(body.mesh.faceCount(), 2 * 13378);
    EXPECT_EQ(body.components, 1);
    EXPECT_EQ(body.boundaryEdges, 0);
    EXPECT_EQ(body.isolatedVertices, 0);
    for (int i = 0; i < body.mesh.vertexCount(); i += 97) {
        const int v = body.sourceVertexIndex[i];
        if (i > 0) EXPECT_LT(body.sourceVertexIndex[i - 1], v);
        EXPECT_EQ(body.mesh.V.row(i), all.mesh.V.row(v));
    }
}

TEST(MeshReaderRealData, KoalaIsOneClosedSurface) {
    const std::string path = dataPath("meshes/koala/koala.obj");
    if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
    const MeshReadResult r = readMesh(path);
    EXPECT_EQ(r.mesh.vertexCount(), 49999);
    EXPECT_EQ(r.mesh.faceCount(), 99994);
    EXPECT_EQ(r.boundaryEdges, 0);
    EXPECT_EQ(r.components, 1);
    EXPECT_EQ(r.mesh.V.row(0), Eigen::RowVector3d(-0.777853, 2.740647, 3.930020));
}

TEST(MeshReaderRealData, HorseThroughEveryFormat) {
    const std::string path = dataPath("sequences/horse-gallop/horse-gallop_0001.obj");
    if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
    const MeshReadResult obj = readMesh(path);
    EXPECT_EQ(obj.mesh.vertexCount(), 8431);
    EXPECT_EQ(obj.mesh.faceCount(), 16843);
    EXPECT_EQ(obj.boundaryEdges, 19);
    EXPECT_EQ(obj.boundaryLoops, 2);

    // OpenMesh delivers floats: compare with the float-rounded OBJ positions. Text OFF is read
    // in double precision, as OBJ is.
    const Positions asFloat = obj.mesh.V.cast<float>().cast<double>();
    Polygons P;
    for (int t = 0; t < obj.mesh.faceCount(); ++t)
        P.push_back({obj.mesh.F(t, 0), obj.mesh.F(t, 1), obj.mesh.F(t, 2)});
    for (const auto& [name, bytes, V] :
         std::vector<std::tuple<std::string, std::string, Positions>>{
             {"horse.ply", plyBinary(asFloat, P), asFloat},
             {"horse.off", offText(obj.mesh.V, P), obj.mesh.V}}) {
        SCOPED_TRACE(name);
        const MeshReadResult r = readMesh(writeFile(name, bytes));
        EXPECT_EQ(r.mesh.V, V);
        EXPECT_EQ(r.mesh.F, obj.mesh.F);
        EXPECT_EQ(r.boundaryLoops, 2);
    }
    // STL: vertex i is the i-th position to appear.
    const MeshReadResult stl = readMesh(writeFile("horse.stl", stlBinary(obj.mesh.V, obj.mesh.F)));
    std::vector<int> firstUse;
    std::vector<char> seen(obj.mesh.vertexCount(), 0);
    for (int c = 0; c < 3 * obj.mesh.faceCount(); ++c) {
        const int v = obj.mesh.F(c / 3, c % 3);
        if (!seen[v]) seen[v] = 1, firstUse.push_back(v);
    }
    ASSERT_EQ(stl.mesh.vertexCount(), static_cast<int>(firstUse.size()));
    for (int i = 0; i < stl.mesh.vertexCount(); ++i)
        ASSERT_EQ(stl.mesh.V.row(i), asFloat.row(firstUse[i])) << i;
    EXPECT_EQ(stl.mesh.faceCount(), obj.mesh.faceCount());
    EXPECT_EQ(stl.boundaryLoops, 2);
}

// ---- What other tools write -------------------------------------------------------------------

// Blender reads an object's name to the end of the line: cut at its space, "Walker Prop" and
// "Walker Body" were one group, and --group "Walker Body" found none.
TEST(MeshReaderFormats, AnObjectsNameIsTheWholeLine) {
    const std::string path = writeFile("spaced.obj", "o Walker Body\n" + objText(tentV(), tentP) +
                                                         "v 5 0 0\nv 6 0 0\nv 5 1 0\n"
                                                         "o Walker Prop\nf 6 7 8\n");
    const auto groups = objGroups(path);
    ASSERT_EQ(groups.size(), 2u);
    EXPECT_EQ(groups[0].name, "Walker Body");
    EXPECT_EQ(groups[1].name, "Walker Prop");
    EXPECT_EQ(readMesh(path, {"Walker Body"}).mesh.vertexCount(), 5);
    EXPECT_EQ(readMesh(path, {"Walker Prop"}).mesh.vertexCount(), 3);
}

// Some converters write a triangle as "f 1 2 3 3". Dropped, it left a hole whose edges the
// manifold check refused; read as the triangle it is, the mesh is whole.
TEST(MeshReaderFormats, ATriangleWrittenWithARepeatedLastCornerIsReadAsATriangle) {
    Polygons P = tentP;
    P[2].push_back(P[2].back());
    for (const std::string& name : {"repeat.obj", "repeat.ply"}) {
        const std::string text = name.back() == 'j' ? objText(tentV(), P) : plyAscii(tentV(), P);
        const MeshReadResult r = readMesh(writeFile(name, text));
        EXPECT_EQ(r.mesh.F, toFaces(tentP)) << name;
        EXPECT_EQ(r.droppedFaces, 0) << name;
        EXPECT_TRUE(anyWarningContains(r, "1 face with a corner repeated in a row")) << name;
    }
    // A face whose corners are not a polygon once read once each is still dropped.
    P[2] = {4, 2, 4, 2};
    const MeshReadResult r = readMesh(writeFile("bowtie.obj", objText(tentV(), P)));
    EXPECT_EQ(r.droppedFaces, 1);
}

// glTF's TEXCOORD_0 must be finite: a "vt nan" reached the .glb.
TEST(MeshReaderFormats, ANonFiniteTextureCoordinateDropsTheFilesCoordinatesWithAWarning) {
    std::string text = "vt 0 0\nvt nan 1\nvt 1 1\n" + objText(tentV(), tentP);
    const MeshReadResult r = readMesh(writeFile("uvnan.obj", text));
    EXPECT_TRUE(anyWarningContains(r, "texture coordinates ignored"));
}

// A cut ascii STL read as the triangles before the cut, and a map made on it animated a fragment.
TEST(MeshReaderErrors, AnAsciiStlCutShortIsRefused) {
    const std::string whole = stlAscii(tentV(), toFaces(tentP));
    EXPECT_NO_THROW(readMesh(writeFile("whole.stl", whole)));
    const std::string cut = whole.substr(0, whole.rfind("outer loop") + 2);
    EXPECT_CONTAINS(errorOf(writeFile("cut.stl", cut)), "it looks cut short");
    const std::string noEnd = whole.substr(0, whole.rfind("endsolid"));
    EXPECT_NO_THROW(readMesh(writeFile("noend.stl", noEnd)));  // complete facets, no endsolid
}

// Frozen with a negative scale (Maya), a body's faces wind inward: its normals point into it, and
// each marker's offset pushed its point into the skin, without a word.
TEST(MeshReaderFormats, ABodyWhoseFacesWindInwardIsSaidToBeInsideOut) {
    Positions V(4, 3);
    V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
    Polygons outward = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}, inward = outward;
    for (auto& f : inward) std::swap(f[1], f[2]);
    EXPECT_FALSE(anyWarningContains(readMesh(writeFile("out.obj", objText(V, outward))), "inward"));
    const MeshReadResult r = readMesh(writeFile("in.obj", objText(V, inward)));
    EXPECT_TRUE(anyWarningContains(r,
                                   "faces wind inward, normals pointing into the body, in the "
                                   "piece of face 0 (line 5)"));
    // An open sheet has no inside: either winding is the user's choice, however fine (a cape of
    // 150 by 150 quads, whose few boundary edges once made it count as nearly closed).
    const int n = 150;
    Positions cape((n + 1) * (n + 1), 3);
    Polygons quads, reversed;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j)
            cape.row(i * (n + 1) + j) << std::cos(M_PI * i / n), std::sin(M_PI * i / n),
                2.0 * j / n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const int a = i * (n + 1) + j;
            quads.push_back({a, a + n + 1, a + n + 2, a + 1});
            reversed.push_back({a, a + 1, a + n + 2, a + n + 1});
        }
    for (const Polygons* P : {&quads, &reversed})
        EXPECT_FALSE(
            anyWarningContains(readMesh(writeFile("cape.obj", objText(cape, *P))), "inward"));
    // The lining of a hollow shell faces into the hollow, as it should.
    Positions shell(8, 3);
    shell << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.2, 0.2, 0.2, 0.4, 0.2, 0.2, 0.2, 0.4, 0.2, 0.2,
        0.2, 0.4;
    Polygons both = outward;
    for (const auto& f : inward) both.push_back({f[0] + 4, f[1] + 4, f[2] + 4});
    EXPECT_FALSE(
        anyWarningContains(readMesh(writeFile("shell.obj", objText(shell, both))), "inward"));
}
