#include "boneless/MeshReader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <unordered_set>

#include "MtlReader.h"
#include "OpenMeshPrecheck.h"
#include "PolygonSoup.h"
#include "boneless/Error.h"
#include "boneless/InputFile.h"
#include "boneless/Text.h"

namespace boneless {

using namespace detail;

namespace {

std::string faceList(const PolygonSoup& soup, const std::vector<int>& faces) {
    std::string s;
    for (size_t i = 0; i < faces.size() && i < 5; ++i)
        s += (i ? ", " : "") + faceWhere(soup, faces[i]);
    return faces.size() > 5 ? s + ", ..." : s;
}

bool hasRepeatedCorner(const int* c, int n) {
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            if (c[i] == c[j]) return true;
    return false;
}

// "f 1 2 3 3", a triangle written as a quad (as some converters write one), is read as the
// polygon without the corner it repeats in a row, as Blender reads it: dropped, it left a hole that
// the manifold check then refused. A face left with fewer than 3 corners is kept whole, to be
// dropped with the warning that says so. Returns the faces changed.
std::vector<int> collapseRepeatedCorners(PolygonSoup& soup) {
    const auto repeats = [&](int f, int k) {
        const int first = soup.faceStart[f], n = soup.faceStart[f + 1] - first;
        return soup.faceIndex[first + k] == soup.faceIndex[first + (k + n - 1) % n];
    };
    std::vector<int> changed;
    for (int f = 0; f < soup.faceCount(); ++f) {
        const int n = soup.faceStart[f + 1] - soup.faceStart[f];
        int left = 0;
        for (int k = 0; k < n; ++k) left += !repeats(f, k);
        if (left < n && left >= 3) changed.push_back(f);
    }
    if (changed.empty()) return changed;
    std::vector<int> index, start{0}, uvOf;
    const bool uv = !soup.uvOf.empty();
    for (int f = 0, next = 0; f < soup.faceCount(); ++f) {
        const bool collapse = next < int(changed.size()) && changed[next] == f;
        next += collapse;
        for (int k = 0, first = soup.faceStart[f]; first + k < soup.faceStart[f + 1]; ++k) {
            if (collapse && repeats(f, k)) continue;
            index.push_back(soup.faceIndex[first + k]);
            if (uv) uvOf.push_back(soup.uvOf[first + k]);
        }
        start.push_back(static_cast<int>(index.size()));
    }
    soup.faceIndex = std::move(index);
    soup.faceStart = std::move(start);
    if (uv) soup.uvOf = std::move(uvOf);
    return changed;
}

// Every face's corners must be vertices of the file; a face that repeats one is dropped. A corner
// past the file's vertices is named as the file writes it: an OBJ's 1-based, at its line (it was
// "vertex 8 ... (0-based) (face 1 (line 5))" for "f 1 3 9", where no number is 8 or face 1);
// OFF's and PLY's 0-based, with the face's 0-based number.
void checkFaces(const std::string& path, const PolygonSoup& soup, bool obj, std::vector<int>& kept,
                std::vector<int>& dropped) {
    const int nv = soup.vertexCount();
    for (int f = 0; f < soup.faceCount(); ++f) {
        const int* c = soup.faceIndex.data() + soup.faceStart[f];
        const int n = soup.faceStart[f + 1] - soup.faceStart[f];
        if (n < 3) throw MeshError(path, "face with " + plural(n, "corner"), faceWhere(soup, f));
        for (int i = 0; i < n; ++i) {
            if (c[i] >= 0 && c[i] < nv) continue;
            const std::string vertices = plural(nv, "vertex", "vertices");
            if (obj && f < static_cast<int>(soup.faceLine.size()))
                throw MeshError(path,
                                "face uses vertex " + std::to_string(c[i] + 1) +
                                    " but the file has " + vertices + " (OBJ indices start at 1)",
                                "line " + std::to_string(soup.faceLine[f]));
            throw MeshError(path,
                            "face uses vertex " + std::to_string(c[i]) + " but the file has " +
                                vertices + " (0-based)",
                            faceWhere(soup, f));
        }
        (hasRepeatedCorner(c, n) ? dropped : kept).push_back(f);
    }
}

void addWarnings(MeshReadResult& r, const PolygonSoup& soup, const std::vector<int>& dropped,
                 const std::vector<int>& zeroArea, const TopologySummary& topo) {
    auto& w = r.warnings;
    if (!dropped.empty())
        w.push_back("dropped " + plural(r.droppedFaces, "face") +
                    " with a repeated vertex: " + faceList(soup, dropped));
    if (r.boundaryEdges > 0)
        w.push_back("open surface: " + plural(r.boundaryEdges, "boundary edge") + " in " +
                    plural(r.boundaryLoops, "loop"));
    if (r.components > 1) w.push_back(plural(r.components, "connected component"));
    if (r.isolatedVertices > 0) {
        std::string list;
        for (size_t i = 0; i < topo.isolated.size(); ++i)
            list += (i ? ", " : "") + std::to_string(topo.isolated[i]);
        w.push_back(plural(r.isolatedVertices, "isolated vertex", "isolated vertices") +
                    " (kept, used by no face): " + list + (r.isolatedVertices > 5 ? ", ..." : ""));
    }
    if (r.zeroAreaFaces > 0)
        w.push_back(plural(r.zeroAreaFaces, "zero-area triangle") + ", from " +
                    faceList(soup, zeroArea));
}

// Reads the material libraries the OBJ names and turns each run's name into the index of its
// definition (a default one for a name no library defines), with a warning for what is missing.
void resolveMaterials(const std::string& path, const PolygonSoup& soup, SourceFaces& out,
                      std::vector<std::string>& warnings) {
    const std::filesystem::path folder = std::filesystem::absolute(path).parent_path();
    for (const std::string& lib : soup.materialLibraries)
        out.materialLibraries.push_back(detail::resolvedPath(folder / lib).string());
    out.materialDefinitions = detail::readMaterialLibraries(out.materialLibraries, warnings);
    if (out.materialLibraries.empty())
        warnings.push_back("uses materials (usemtl) but names no material library (mtllib)");
    auto& defined = out.materialDefinitions;
    std::vector<int> definitionOf(soup.materialNames.size(), -1);
    std::vector<int> placed;  // per definition: -1 unused, else whether a corner of it has a "vt"
    for (size_t run = 0; run < out.materials.size(); ++run) {
        int& material = out.materials[run].second;
        int& d = definitionOf[material];
        if (d < 0) {
            const std::string& name = soup.materialNames[material];
            const auto it = std::find_if(defined.begin(), defined.end(),
                                         [&](const ObjMaterial& m) { return m.name == name; });
            d = static_cast<int>(it - defined.begin());
            if (it == defined.end()) {
                if (!out.materialLibraries.empty())
                    warnings.push_back("material '" + name + "' is used but no mtllib defines it");
                defined.push_back(ObjMaterial{});
                defined.back().name = name;
            }
        }
        material = d;
        placed.resize(defined.size(), -1);
        placed[d] = std::max(placed[d], 0);
        const int end =
            run + 1 < out.materials.size() ? out.materials[run + 1].first : out.polygonCount();
        for (int c = out.start[out.materials[run].first]; c < out.start[end] && !out.uvOf.empty();
             ++c)
            if (out.uvOf[c] >= 0) placed[d] = 1;
    }
    for (size_t d = 0; d < placed.size(); ++d)
        if (placed[d] == 0 && !(defined[d].texture.empty() && defined[d].normalTexture.empty()))
            warnings.push_back("material '" + defined[d].name +
                               "' has a texture, but its faces have no texture coordinates (vt) "
                               "to place it");
}

// The kept faces as the file has them, with their texture coordinates (only those they use) and
// materials, when that is more than the triangles say; null otherwise.
std::shared_ptr<const SourceFaces> sourceFaces(const std::string& path, const PolygonSoup& soup,
                                               const std::vector<int>& kept,
                                               const std::vector<int>& meshIndex, int vertexCount,
                                               std::vector<std::string>& warnings) {
    const bool uvs = !soup.uvOf.empty() && !soup.uv.empty();
    bool polygons = false, anyUv = false, anyMaterial = false;
    for (int f : kept) {
        polygons |= soup.faceStart[f + 1] - soup.faceStart[f] > 3;
        anyMaterial |= !soup.faceMaterial.empty() && soup.faceMaterial[f] >= 0;
        if (uvs)
            for (int c = soup.faceStart[f]; c < soup.faceStart[f + 1]; ++c)
                anyUv |= soup.uvOf[c] >= 0;
    }
    if (!polygons && !anyUv && !anyMaterial) return nullptr;
    auto out = std::make_shared<SourceFaces>();
    out->vertexCount = vertexCount;
    std::vector<int> uvIndex(soup.uv.size() / 2, -1);
    // The previous polygon's, into soup.materialNames until resolved below. A bare "usemtl" keeps
    // the material before it, as Blender's importer does (the format does not say).
    int material = -1;
    for (int f : kept) {
        if (anyMaterial && soup.faceMaterial[f] >= 0 && soup.faceMaterial[f] != material) {
            material = soup.faceMaterial[f];
            out->materials.push_back({out->polygonCount(), material});
        }
        for (int c = soup.faceStart[f]; c < soup.faceStart[f + 1]; ++c) {
            out->corners.push_back(meshIndex[soup.faceIndex[c]]);
            if (!anyUv) continue;
            const int t = soup.uvOf[c];
            if (t >= 0 && uvIndex[t] < 0) {
                uvIndex[t] = static_cast<int>(out->uv.size() / 2);
                out->uv.insert(out->uv.end(), {soup.uv[2 * t], soup.uv[2 * t + 1]});
            }
            out->uvOf.push_back(t >= 0 ? uvIndex[t] : -1);
        }
        out->start.push_back(static_cast<int>(out->corners.size()));
    }
    if (anyMaterial) resolveMaterials(path, soup, *out, warnings);
    return out;
}

}  // namespace

MeshReadResult readMesh(const std::string& path, const MeshReadOptions& options) {
    if (const std::string why = notARegularFile(path, "mesh"); !why.empty())
        throw MeshError(path, why);
    const bool obj = lowerExtension(path) == "obj";
    if (!options.group.empty() && !obj)
        throw MeshError(path, "only OBJ files have groups", "group '" + options.group + "'");
    PolygonSoup soup = obj ? readObj(path, options.group) : readWithOpenMesh(path);
    const std::vector<int> collapsed = collapseRepeatedCorners(soup);

    MeshReadResult r;
    r.warnings = soup.warnings;
    if (!collapsed.empty())
        r.warnings.push_back(plural(int(collapsed.size()), "face") +
                             " with a corner repeated in a row (a triangle written as 'f 1 2 3 "
                             "3'), read with it once: " +
                             faceList(soup, collapsed));
    r.sourceVertexCount = soup.vertexCount();
    r.sourceFaceCount = soup.faceCount();
    const int nv = soup.vertexCount();

    std::vector<int> kept, dropped;
    checkFaces(path, soup, obj, kept, dropped);

    // Whole file: every vertex, so that vertex i stays file vertex i. Group: the vertices its
    // faces use, in file order.
    std::vector<int> meshIndex(nv, -1);
    if (options.group.empty()) {
        for (int v = 0; v < nv; ++v) meshIndex[v] = v;
    } else {
        for (int i : soup.faceIndex) meshIndex[i] = 0;
    }
    for (int v = 0; v < nv; ++v) {
        if (meshIndex[v] < 0) continue;
        meshIndex[v] = static_cast<int>(r.sourceVertexIndex.size());
        r.sourceVertexIndex.push_back(v);
    }

    Positions& V = r.mesh.V;
    V.resize(static_cast<Eigen::Index>(r.sourceVertexIndex.size()), 3);
    for (int i = 0; i < V.rows(); ++i) {
        const int v = r.sourceVertexIndex[i];
        for (int k = 0; k < 3; ++k) V(i, k) = soup.xyz[3 * size_t(v) + k];
        if (!V.row(i).allFinite())
            throw MeshError(path, "non-finite vertex coordinate", vertexWhere(soup, v));
        // Every output but OBJ stores floats: beyond their range it would hold infinities.
        for (int k = 0; k < 3; ++k)
            if (std::abs(V(i, k)) > std::numeric_limits<float>::max())
                throw MeshError(path,
                                "vertex coordinate " + shortNumber(V(i, k)) +
                                    " is beyond the range of a float (3.4e38), which glTF, MDD "
                                    "and PC2 store",
                                vertexWhere(soup, v));
    }

    int welded = 0;
    const std::vector<int> weld = weldCopies(V, soup, kept, meshIndex, welded);
    for (int& v : meshIndex)
        if (v >= 0) v = weld[v];
    // The file's edges, so that no diagonal the triangulation cuts doubles one of them.
    std::unordered_set<uint64_t> sides;
    for (int f : kept)
        for (int c = soup.faceStart[f], end = soup.faceStart[f + 1]; c < end; ++c)
            sides.insert(
                edgeKey(meshIndex[soup.faceIndex[c]],
                        meshIndex[soup.faceIndex[c + 1 < end ? c + 1 : soup.faceStart[f]]]));
    std::unordered_set<uint64_t> edges = std::move(sides), repeated;
    std::vector<int> tris, polygon, triFace;  // triFace: soup face of each triangle
    for (int f : kept) {
        const int n = soup.faceStart[f + 1] - soup.faceStart[f];
        polygon.assign(soup.faceIndex.begin() + soup.faceStart[f],
                       soup.faceIndex.begin() + soup.faceStart[f] + n);
        for (int& c : polygon) c = meshIndex[c];
        triangulatePolygon(V, polygon.data(), n, edges, tris, repeated);
        triFace.insert(triFace.end(), n - 2, f);
        if (n > 3) ++r.polygonsTriangulated;
    }
    r.droppedFaces = static_cast<int>(dropped.size());
    for (int f : triFace) r.sourceFaceIndex.push_back(soup.fileFaceOf(f));
    if (tris.empty()) {
        const std::string what = !options.group.empty()
                                     ? "group '" + options.group + "' has no usable faces"
                                 : soup.faceCount() == 0 ? "no faces (nothing to animate)"
                                                         : "no usable faces";
        throw MeshError(path, what, dropped.empty() ? "" : "every face repeats a vertex");
    }
    r.mesh.F = Eigen::Map<const Faces>(tris.data(), static_cast<Eigen::Index>(tris.size() / 3), 3);

    const TopologySummary topo = checkManifold(path, r.mesh.F, r.mesh.vertexCount(), triFace, soup,
                                               r.sourceVertexIndex, repeated, weld);
    r.boundaryEdges = topo.boundaryEdges;
    r.boundaryLoops = topo.boundaryLoops;
    r.components = topo.components;
    r.isolatedVertices = topo.isolatedVertices;

    // Scaled by the vertices faces use: an isolated one far away made every triangle flat.
    const double diagonal = boundingBoxDiagonal(V, r.mesh.F);
    std::vector<int> flat;  // the polygons they come from, each once (its triangles are adjacent)
    for (int t = 0; t < r.mesh.faceCount(); ++t)
        if (zeroArea(V.row(r.mesh.F(t, 0)), V.row(r.mesh.F(t, 1)), V.row(r.mesh.F(t, 2)),
                     diagonal)) {
            ++r.zeroAreaFaces;
            if (flat.size() < 6 && (flat.empty() || flat.back() != triFace[t]))
                flat.push_back(triFace[t]);
        }

    addWarnings(r, soup, dropped, flat, topo);
    if (const std::vector<int> inward = insideOutPieces(V, r.mesh.F); !inward.empty()) {
        std::vector<int> faces;
        for (int t : inward) faces.push_back(triFace[t]);
        r.warnings.push_back(
            "faces wind inward, normals pointing into the body, in the piece of " +
            faceList(soup, faces) +
            ": a marker's offset_mm pushes it into the skin; turn the normals outward (Blender: "
            "Mesh > Normals > Recalculate Outside) and save the mesh again");
    }
    // The file's own corners, copies and all: their texture coordinates tell the copies apart.
    for (int i = 0; i < V.rows(); ++i) meshIndex[r.sourceVertexIndex[i]] = i;
    r.mesh.sourceFaces = sourceFaces(path, soup, kept, meshIndex, r.mesh.vertexCount(), r.warnings);
    if (welded > 0) {
        r.mesh.weldedTo = weld;
        r.weldedVertices = welded;
        r.warnings.push_back("welded " + plural(welded, "vertex", "vertices") +
                             " that share a position with another (split UV seams)");
    }
    return r;
}

std::vector<ObjGroup> objGroups(const std::string& path) {
    if (lowerExtension(path) != "obj") return {};
    if (const std::string why = notARegularFile(path, "mesh"); !why.empty())
        throw MeshError(path, why);
    return readObjGroups(path);
}

}  // namespace boneless
