// Binary OFF and STL through OpenMesh's readers (text OFF and PLY are read by the precheck), into a
// PolygonSoup. The importer below records what the readers deliver and builds no topology, so
// vertex order stays the file's and non-manifold input reaches our own checks instead of
// OpenMesh's silent vertex duplication.

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <filesystem>
#include <mutex>
#include <sstream>

#include "OpenMeshPrecheck.h"
#include "PolygonSoup.h"
#include "boneless/Error.h"

namespace boneless::detail {

namespace {

using namespace OpenMesh;

class SoupImporter : public IO::BaseImporter {
  public:
    // inputBytes bounds what a header may make us reserve: no vertex or face takes under 4 bytes.
    SoupImporter(PolygonSoup& soup, std::size_t inputBytes)
        : soup_(soup), mostElements_(inputBytes / 4 + 1) {}

    VertexHandle add_vertex(const Vec3f& p) override { return add_vertex(Vec3d(p)); }
    VertexHandle add_vertex(const Vec3d& p) override {
        soup_.xyz.insert(soup_.xyz.end(), {p[0], p[1], p[2]});
        return VertexHandle(soup_.vertexCount() - 1);
    }
    VertexHandle add_vertex() override { return add_vertex(Vec3d(0, 0, 0)); }
    void set_point(VertexHandle v, const Vec3f& p) override {
        if (!v.is_valid() || v.idx() >= soup_.vertexCount()) return;
        for (int k = 0; k < 3; ++k) soup_.xyz[3 * v.idx() + k] = p[k];
    }
    FaceHandle add_face(const VHandles& corners) override {
        for (const VertexHandle& v : corners) soup_.faceIndex.push_back(v.idx());
        soup_.endFace();
        return FaceHandle(soup_.faceCount() - 1);
    }
    void reserve(unsigned int nV, unsigned int, unsigned int nF) override {
        const std::size_t vertices = std::min<std::size_t>(nV, mostElements_);
        const std::size_t faces = std::min<std::size_t>(nF, mostElements_);
        soup_.xyz.reserve(3 * vertices);
        soup_.faceStart.reserve(faces + 1);
        soup_.faceIndex.reserve(3 * faces);
    }
    size_t n_vertices() const override { return soup_.vertexCount(); }
    size_t n_faces() const override { return soup_.faceCount(); }
    size_t n_edges() const override { return 0; }

    // Connectivity-by-halfedge (OM format only) and attributes: not ours to keep.
    HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
    FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
    void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<Vec2f>&) override {}
    void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<Vec3f>&) override {}
    void set_face_texindex(FaceHandle, int) override {}
    void set_halfedge(VertexHandle, HalfedgeHandle) override {}
    void set_normal(VertexHandle, const Vec3f&) override {}
    void set_normal(VertexHandle, const Vec3d&) override {}
    void set_color(VertexHandle, const Vec3uc&) override {}
    void set_color(VertexHandle, const Vec4uc&) override {}
    void set_color(VertexHandle, const Vec3f&) override {}
    void set_color(VertexHandle, const Vec4f&) override {}
    void set_texcoord(VertexHandle, const Vec2f&) override {}
    void set_status(VertexHandle, const Attributes::StatusInfo&) override {}
    void set_next(HalfedgeHandle, HalfedgeHandle) override {}
    void set_face(HalfedgeHandle, FaceHandle) override {}
    void request_face_texcoords2D() override {}
    void set_texcoord(HalfedgeHandle, const Vec2f&) override {}
    void set_texcoord(VertexHandle, const Vec3f&) override {}
    void set_texcoord(HalfedgeHandle, const Vec3f&) override {}
    void set_status(HalfedgeHandle, const Attributes::StatusInfo&) override {}
    void set_color(EdgeHandle, const Vec3uc&) override {}
    void set_color(EdgeHandle, const Vec4uc&) override {}
    void set_color(EdgeHandle, const Vec3f&) override {}
    void set_color(EdgeHandle, const Vec4f&) override {}
    void set_status(EdgeHandle, const Attributes::StatusInfo&) override {}
    void set_normal(FaceHandle, const Vec3f&) override {}
    void set_normal(FaceHandle, const Vec3d&) override {}
    void set_color(FaceHandle, const Vec3uc&) override {}
    void set_color(FaceHandle, const Vec4uc&) override {}
    void set_color(FaceHandle, const Vec3f&) override {}
    void set_color(FaceHandle, const Vec4f&) override {}
    void set_status(FaceHandle, const Attributes::StatusInfo&) override {}
    void add_texture_information(int, std::string) override {}

  private:
    PolygonSoup& soup_;
    std::size_t mostElements_;
};

// OpenMesh writes diagnostics to its global streams omerr/omlog/omout, which forward to
// std::cerr/clog/cout. While a read runs, their stream buffer is swapped for ours, so what
// OpenMesh says becomes our warnings and errors instead of console noise. (Swapping the buffer
// rather than disconnecting the console target: OpenMesh's disconnect leaks its target object.)
// The streams are process-wide, hence the lock, which also serialises OpenMesh's IOManager.
class OpenMeshLogCapture {
  public:
    OpenMeshLogCapture() : lock_(mutex()) {
        for (int s = 0; s < 3; ++s) saved_[s] = stream(s).rdbuf(&text_);
    }
    ~OpenMeshLogCapture() {
        for (int s = 0; s < 3; ++s) stream(s).rdbuf(saved_[s]);
    }
    void note(const std::string& message) {
        text_.sputn((message + "\n").data(), message.size() + 1);
    }
    std::vector<std::string> lines() {
        std::vector<std::string> out;
        std::istringstream in(text_.str());
        for (std::string line; std::getline(in, line);) {
            const size_t b = line.find_first_not_of(" \t\r"), e = line.find_last_not_of(" \t\r");
            if (b != std::string::npos) out.push_back(line.substr(b, e - b + 1));
        }
        return out;
    }

  private:
    static std::mutex& mutex() {
        static std::mutex m;
        return m;
    }
    static std::ostream& stream(int s) { return s == 0 ? omerr() : s == 1 ? omlog() : omout(); }

    std::lock_guard<std::mutex> lock_;
    std::stringbuf text_;
    std::streambuf* saved_[3] = {};
};

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += (s.empty() ? "" : "; ") + l;
    return s;
}

}  // namespace

PolygonSoup readWithOpenMesh(const std::string& path) {
    Precheck facts = precheckForOpenMesh(path);
    if (facts.soup) return std::move(*facts.soup);
    PolygonSoup soup;
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
    SoupImporter importer(soup, ec ? 0 : bytes);
    IO::Options options;  // no attributes: positions and faces only
    bool ok;
    std::vector<std::string> messages;
    {
        OpenMeshLogCapture capture;
        try {
            // By path, so that each reader parses this file's header afresh.
            ok = IO::IOManager().read(path, importer, options);
        } catch (const std::exception& e) {
            ok = false;
            capture.note(e.what());
        }
        messages = capture.lines();
    }
    if (!ok) {
        throw MeshError(path, "OpenMesh could not read the file",
                        messages.empty() ? std::string() : joined(messages));
    }
    // Said once each: a reader may parse a header twice (once to see whether it can read it).
    for (size_t i = 0; i < messages.size(); ++i) {
        const std::string& m = messages[i];
        if (std::find(messages.begin(), messages.begin() + i, m) == messages.begin() + i)
            soup.warnings.push_back("OpenMesh: " + m);
    }
    if (facts.stl && facts.triangles > soup.faceCount()) {
        soup.warnings.push_back(
            std::to_string(facts.triangles - soup.faceCount()) +
            " STL triangle(s) with coinciding corners dropped (OpenMesh merges equal positions)");
    }
    if (facts.declaredVertices >= 0 && facts.declaredVertices != soup.vertexCount()) {
        throw MeshError(path, "header announces " + std::to_string(facts.declaredVertices) +
                                  " vertices but " + std::to_string(soup.vertexCount()) +
                                  " were read");
    }
    if (facts.declaredFaces >= 0 && facts.declaredFaces != soup.faceCount()) {
        throw MeshError(path, "header announces " + std::to_string(facts.declaredFaces) +
                                  " faces but " + std::to_string(soup.faceCount()) + " were read");
    }
    return soup;
}

}  // namespace boneless::detail
