#include "boneless/GltfWriter.h"

#include <tiny_gltf.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unordered_map>

#include "MtlReader.h"
#include "boneless/Error.h"
#include "boneless/SpoolFile.h"
#include "boneless/Text.h"

namespace boneless {

// What a .glb's length depends on besides its frame count.
struct GlbShape {
    std::uint64_t vertices = 0, triangles = 0, uvFloats = 0, textureBytes = 0, primitives = 1;
};

namespace {

// The GLB container stores chunk lengths as uint32.
constexpr std::uint64_t kMaxGlbBytes = std::numeric_limits<std::uint32_t>::max() - (1u << 20);

// The .glb's length with `frames` frames: the rest mesh and its normals, each frame's position
// and normal offsets, the times, the dense weight keys (frames × frames floats) and the JSON,
// estimated (each frame adds two accessors, two views, a name and a target per primitive).
std::uint64_t glbBytes(const GlbShape& s, std::uint64_t frames) {
    return 4096 + 24 * s.vertices * (frames + 1) + 4 * s.uvFloats + 12 * s.triangles +
           s.textureBytes + 4 * frames + 4 * frames * frames + frames * (450 + 40 * s.primitives);
}

// Area-weighted vertex normals of the triangles F over V: each triangle's cross product (twice its
// area along its normal) summed at its corners, normalised. glTF wants unit normals, so a vertex
// no triangle uses, or only degenerate ones, gets +Z.
Positions vertexNormals(const Positions& V, const Faces& F) {
    Positions n = Positions::Zero(V.rows(), 3);
    for (int t = 0; t < F.rows(); ++t) {
        const Vec3 a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
        const Vec3 cross = (b - a).cross(c - a);
        for (int k = 0; k < 3; ++k) n.row(F(t, k)) += cross;
    }
    for (int v = 0; v < n.rows(); ++v) {
        const double length = n.row(v).norm();
        if (length > 0 && std::isfinite(length))
            n.row(v) /= length;
        else
            n.row(v) = Vec3::UnitZ();
    }
    return n;
}

std::string tooLarge(const std::string& path, const GlbShape& s, std::uint64_t frames) {
    std::uint64_t fit = 0, over = 1 << 20;  // glbBytes(fit) fits, glbBytes(over) does not
    while (over - fit > 1) {
        const std::uint64_t mid = (fit + over) / 2;
        (glbBytes(s, mid) <= kMaxGlbBytes ? fit : over) = mid;
    }
    char size[32];
    std::snprintf(size, sizeof size, "%.1f GB", glbBytes(s, frames) / 1e9);
    return path + ": " + std::to_string(frames) + " frames make a .glb of about " + size +
           ", more than the 4.29 GB (2^32 bytes) a .glb can hold (the weight keys alone take "
           "frames² × 4 bytes); export at most " +
           std::to_string(fit) +
           " frames of this mesh at a time (solve's --frames A:B, the app's "
           "Frames … to …), or a point cache";
}

int addView(tinygltf::Model& m, size_t offset, size_t length, int target = 0) {
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = length;
    view.target = target;
    m.bufferViews.push_back(view);
    return static_cast<int>(m.bufferViews.size()) - 1;
}

int addAccessor(tinygltf::Model& m, int view, int componentType, int type, size_t count,
                std::vector<double> min = {}, std::vector<double> max = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    m.accessors.push_back(a);
    return static_cast<int>(m.accessors.size()) - 1;
}

template <class T>
void appendBytes(std::string& out, const std::vector<T>& values) {
    out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

void appendU32(std::string& out, std::uint32_t v) {  // GLB is little-endian, as is the build
    out.append(reinterpret_cast<const char*>(&v), 4);
}

// The scene: one node with the mesh, its morph targets named, and an animation that steps
// through them (none without frames).
void addAnimatedMesh(tinygltf::Model& m, const std::string& name, const GltfPlacement& placement,
                     std::vector<tinygltf::Primitive> primitives,
                     std::vector<tinygltf::Value> targetNames, int timeAccessor,
                     int weightAccessor) {
    const size_t frames = targetNames.size();
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives = std::move(primitives);
    mesh.weights.assign(frames, 0.0);
    mesh.extras = tinygltf::Value(
        tinygltf::Value::Object{{"targetNames", tinygltf::Value(std::move(targetNames))}});
    m.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = name;
    node.mesh = 0;
    const Eigen::Quaterniond q(placement.turn);
    if (!q.isApprox(Eigen::Quaterniond::Identity())) node.rotation = {q.x(), q.y(), q.z(), q.w()};
    if (placement.metresPerUnit != 1.0) node.scale.assign(3, placement.metresPerUnit);
    m.nodes.push_back(node);
    m.scenes.emplace_back();
    m.scenes[0].nodes = {0};
    m.defaultScene = 0;
    if (frames > 0) {
        tinygltf::Animation animation;
        animation.name = name;
        tinygltf::AnimationSampler sampler;
        sampler.input = timeAccessor;
        sampler.output = weightAccessor;
        sampler.interpolation = "LINEAR";
        animation.samplers.push_back(sampler);
        tinygltf::AnimationChannel channel;
        channel.sampler = 0;
        channel.target_node = 0;
        channel.target_path = "weights";
        animation.channels.push_back(channel);
        m.animations.push_back(animation);
    }
}

// tinygltf writes the document; the buffer's bytes are streamed from the spool, so its entry
// is replaced by one that names the BIN chunk's length. Padded to 4 bytes, as GLB chunks are.
std::string glbJson(const tinygltf::Model& m, size_t binLength) {
    std::ostringstream text;
    tinygltf::TinyGLTF gltf;
    gltf.WriteGltfSceneToStream(&m, text, false, false);
    nlohmann::json document = nlohmann::json::parse(text.str());
    document["buffers"] = nlohmann::json::array({{{"byteLength", binLength}}});
    std::string json = document.dump();
    json.append((4 - json.size() % 4) % 4, ' ');
    return json;
}

// glTF has one texture coordinate per vertex: each (mesh vertex, coordinate) pair the triangles'
// corners use becomes a glTF vertex. The triangles are the source polygons' in order, n - 2 each
// (readMesh); false when they are not, or there are no coordinates.
bool splitAtUvSeams(const TriMesh& mesh, std::vector<int>& meshVertexOf, std::vector<float>& uv,
                    std::vector<std::uint32_t>& triangles) {
    const SourceFaces* source = mesh.sourceFaces.get();
    if (!source || source->uvOf.empty()) return false;
    std::unordered_map<std::int64_t, std::uint32_t> index;
    int t = 0;
    for (int p = 0; p < source->polygonCount(); ++p) {
        const int first = source->start[p], n = source->start[p + 1] - first;
        for (int k = 0; k < n - 2; ++k, ++t) {
            if (t >= mesh.F.rows()) return false;
            for (int c = 0; c < 3; ++c) {
                const int v = mesh.F(t, c);
                // F names a welded vertex where the polygon may name its copy.
                const int* corner =
                    std::find_if(&source->corners[first], &source->corners[first] + n,
                                 [&](int u) { return weldedVertex(mesh, u) == v; });
                if (corner == &source->corners[first] + n) return false;
                const int coordinate = source->uvOf[corner - source->corners.data()];
                const auto [it, added] =
                    index.emplace(std::int64_t(v) << 32 | std::uint32_t(coordinate),
                                  static_cast<std::uint32_t>(meshVertexOf.size()));
                if (added) {
                    meshVertexOf.push_back(v);
                    const bool has = coordinate >= 0;
                    uv.push_back(has ? static_cast<float>(source->uv[2 * coordinate]) : 0.0f);
                    uv.push_back(has ? static_cast<float>(1.0 - source->uv[2 * coordinate + 1])
                                     : 0.0f);
                }
                triangles.push_back(it->second);
            }
        }
    }
    return t == mesh.F.rows();
}

// The material of each triangle, as an index into `used` (−1: none), from the source polygons'
// "usemtl" runs; triangles follow the polygons, n − 2 each (readMesh). Empty when the mesh has no
// materials or its triangles do not follow its polygons.
std::vector<int> triangleMaterials(const TriMesh& mesh, std::vector<ObjMaterial>& usedOut) {
    const SourceFaces* source = mesh.sourceFaces.get();
    if (!source || source->materials.empty()) return {};
    std::vector<ObjMaterial> used;  // given back only if the triangles follow the polygons
    std::vector<int> out;
    out.reserve(static_cast<size_t>(mesh.faceCount()));
    std::vector<int> usedIndex(source->materialDefinitions.size(), -1);
    size_t run = 0;
    int material = -1;
    for (int p = 0; p < source->polygonCount(); ++p) {
        if (run < source->materials.size() && source->materials[run].first == p) {
            const int d = source->materials[run++].second;
            if (usedIndex[d] < 0) {
                usedIndex[d] = static_cast<int>(used.size());
                used.push_back(source->materialDefinitions[d]);
            }
            material = usedIndex[d];
        }
        out.insert(out.end(), source->start[p + 1] - source->start[p] - 2, material);
    }
    if (out.size() != static_cast<size_t>(mesh.faceCount())) return {};
    usedOut = std::move(used);
    return out;
}

// A map's -o and -s as KHR_texture_transform, which Blender's, three.js's and Unity's glTF readers
// apply: dropped, the glb showed another tiling than the OBJ frames. glTF's v runs down the image
// (the writer stores 1 - v), so the v offset is 1 - s - o.
tinygltf::ExtensionMap textureTransform(const TextureTransform& t) {
    if (t.identity()) return {};
    using tinygltf::Value;
    Value::Object transform;
    transform["offset"] =
        Value(Value::Array{Value(t.offset[0]), Value(1 - t.scale[1] - t.offset[1])});
    transform["scale"] = Value(Value::Array{Value(t.scale[0]), Value(t.scale[1])});
    return {{"KHR_texture_transform", Value(transform)}};
}

// An OBJ material as glTF's metallic-roughness one: not metallic, as rough as Blender reads its
// Ns. With a texture the colour is the texture's (OBJ importers show map_Kd in place of Kd).
tinygltf::Material gltfMaterial(const ObjMaterial& obj, int texture, int normalTexture) {
    tinygltf::Material m;
    m.name = validUtf8(obj.name);
    auto& pbr = m.pbrMetallicRoughness;
    // glTF's factors lie in [0, 1]; an OBJ's Kd may not.
    const auto unit = [](double x) { return std::clamp(x, 0.0, 1.0); };
    pbr.baseColorFactor = {unit(obj.colour[0]), unit(obj.colour[1]), unit(obj.colour[2]),
                           obj.opacity};
    if (texture >= 0) {
        pbr.baseColorFactor = {1.0, 1.0, 1.0, obj.opacity};
        pbr.baseColorTexture.index = texture;
        pbr.baseColorTexture.extensions = textureTransform(obj.textureTransform);
    }
    pbr.metallicFactor = 0;
    pbr.roughnessFactor = obj.roughness;
    if (normalTexture >= 0) {
        m.normalTexture.index = normalTexture;
        m.normalTexture.scale = obj.normalScale;
        m.normalTexture.extensions = textureTransform(obj.normalTransform);
    }
    if (obj.opacity < 1) m.alphaMode = "BLEND";
    return m;
}

// A texture's bytes, or empty if it can no longer be read (the export goes on without it).
std::string readImage(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return in ? bytes.str() : std::string();
}

// The glTF vertices (split at UV seams), their coordinates, the triangles grouped by material,
// and the bytes of the textures they embed.
void layOut(const TriMesh& rest, std::vector<int>& meshVertexOf, std::vector<float>& uv,
            std::vector<std::uint32_t>& triangles, std::vector<ObjMaterial>& usedMaterials,
            std::vector<std::pair<int, size_t>>& groups, std::uint64_t& textureBytes) {
    if (!splitAtUvSeams(rest, meshVertexOf, uv, triangles)) {
        meshVertexOf.resize(static_cast<size_t>(rest.vertexCount()));
        for (int v = 0; v < rest.vertexCount(); ++v) meshVertexOf[v] = v;
        uv.clear();
        triangles.assign(rest.F.data(), rest.F.data() + rest.F.size());
    }
    // One glTF primitive per material: the triangles grouped by it, in their order within.
    const std::vector<int> material = triangleMaterials(rest, usedMaterials);
    if (!material.empty()) {
        std::vector<std::uint32_t> grouped;
        grouped.reserve(triangles.size());
        for (int g = -1; g < static_cast<int>(usedMaterials.size()); ++g) {
            const size_t before = grouped.size();
            for (size_t t = 0; t < material.size(); ++t)
                if (material[t] == g)
                    grouped.insert(grouped.end(), &triangles[3 * t], &triangles[3 * t] + 3);
            if (grouped.size() > before) groups.push_back({g, (grouped.size() - before) / 3});
        }
        triangles = std::move(grouped);
    }
    std::vector<std::string> textures;
    for (const ObjMaterial& obj : usedMaterials)
        for (const std::string& texture : {obj.texture, obj.normalTexture}) {
            if (uv.empty() || texture.empty() ||
                std::find(textures.begin(), textures.end(), texture) != textures.end())
                continue;
            textures.push_back(texture);
            std::error_code error;
            const std::uintmax_t size = std::filesystem::file_size(texture, error);
            if (!error) textureBytes += size + 3;
        }
}

// What a .glb's length depends on, from layOut's results: the check before solving and the
// writer's own must count the same file.
GlbShape glbShape(const std::vector<int>& meshVertexOf, const std::vector<float>& uv,
                  const std::vector<std::uint32_t>& triangles,
                  const std::vector<std::pair<int, size_t>>& groups, std::uint64_t textureBytes) {
    GlbShape s;
    s.vertices = meshVertexOf.size();
    s.triangles = triangles.size() / 3;
    s.uvFloats = uv.size();
    s.textureBytes = textureBytes;
    s.primitives = std::max<std::uint64_t>(groups.size(), 1);
    return s;
}

}  // namespace

void checkGlbFits(const std::string& path, const TriMesh& mesh, int frames) {
    std::vector<int> meshVertexOf;
    std::vector<float> uv;
    std::vector<std::uint32_t> triangles;
    std::vector<ObjMaterial> usedMaterials;
    std::vector<std::pair<int, size_t>> groups;
    std::uint64_t textureBytes = 0;
    layOut(mesh, meshVertexOf, uv, triangles, usedMaterials, groups, textureBytes);
    const GlbShape shape = glbShape(meshVertexOf, uv, triangles, groups, textureBytes);
    if (frames > 0 && glbBytes(shape, frames) > kMaxGlbBytes)
        throw Error(tooLarge(path, shape, frames));
}

GltfWriter::GltfWriter(std::string path, const TriMesh& rest, std::string name,
                       GltfPlacement placement)
    : path_(std::move(path)), name_(std::move(name)), rest_(rest), placement_(placement) {
    layOut(rest_, meshVertexOf_, uv_, triangles_, usedMaterials_, groups_, textureBytes_);
    restNormals_ = vertexNormals(rest_.V, rest_.F);
    file_ = openSpoolBeside(path_);
}

GltfWriter::~GltfWriter() {
    if (file_) std::fclose(file_);
}

void GltfWriter::append(int frame, double seconds, const Positions& positions) {
    if (!file_) throw Error(path_ + ": the glTF file is already finished");
    const int n = rest_.vertexCount();
    if (positions.rows() != n)
        throw Error(path_ + ": frame with " + std::to_string(positions.rows()) +
                    " vertices, the mesh has " + std::to_string(n));
    const std::uint64_t m = meshVertexOf_.size();
    if (glbBytes(shape(), times_.size() + 1) > kMaxGlbBytes)
        throw Error(tooLarge(path_, shape(), times_.size() + 1));
    // The position offsets, then the normals' (a UV seam's copies of a vertex share its normal,
    // so no seam shows): Unity's blend shapes move the shading only by the normal offsets.
    const Positions normals = vertexNormals(positions, rest_.F);
    std::vector<float> offsets(6 * m);
    std::array<double, 6> b = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (size_t i = 0; i < m; ++i)
        for (int c = 0; c < 3; ++c) {
            const int v = meshVertexOf_[i];
            const float d = static_cast<float>(positions(v, c) - rest_.V(v, c));
            offsets[3 * i + c] = d;
            offsets[3 * (m + i) + c] = static_cast<float>(normals(v, c) - restNormals_(v, c));
            b[c] = std::min(b[c], double(d));
            b[3 + c] = std::max(b[3 + c], double(d));
        }
    if (std::fwrite(offsets.data(), sizeof(float), offsets.size(), file_) != offsets.size())
        throw Error(path_ + ": writing failed (" + writeFailure() + ")");
    times_.push_back(static_cast<float>(seconds));
    frames_.push_back(frame);
    bounds_.push_back(b);
}

GlbShape GltfWriter::shape() const {
    return glbShape(meshVertexOf_, uv_, triangles_, groups_, textureBytes_);
}

void GltfWriter::finish() {
    if (!file_) return;
    const int n = static_cast<int>(meshVertexOf_.size());  // glTF vertices
    const size_t frames = times_.size();
    tinygltf::Model m;
    m.asset.version = "2.0";
    m.asset.generator = "Boneless";
    m.buffers.emplace_back();

    // BIN chunk: rest positions and normals, triangles, texture coordinates, textures, the
    // spooled offsets (positions, normals, a frame at a time), times, weight keys.
    std::string head;
    std::vector<float> rest(3 * static_cast<size_t>(n)), restNormals(rest.size());
    std::vector<double> lo(3, 1e300), hi(3, -1e300);
    for (int v = 0; v < n; ++v)
        for (int c = 0; c < 3; ++c) {
            rest[3 * v + c] = static_cast<float>(rest_.V(meshVertexOf_[v], c));
            restNormals[3 * v + c] = static_cast<float>(restNormals_(meshVertexOf_[v], c));
            lo[c] = std::min(lo[c], double(rest[3 * v + c]));
            hi[c] = std::max(hi[c], double(rest[3 * v + c]));
        }
    const std::vector<std::uint32_t>& triangles = triangles_;
    size_t offset = 0;
    auto place = [&](size_t length, int target = 0) {
        const int view = addView(m, offset, length, target);
        offset += length;
        return view;
    };
    const int restAccessor =
        addAccessor(m, place(rest.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n, lo, hi);
    const int normalAccessor =
        addAccessor(m, place(restNormals.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
    const int triangleView = place(triangles.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = restAccessor;
    primitive.attributes["NORMAL"] = normalAccessor;
    if (!uv_.empty())
        primitive.attributes["TEXCOORD_0"] =
            addAccessor(m, place(uv_.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, uv_.size() / 2);
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    // The materials, their textures in the BIN chunk after the coordinates (a texture needs
    // them), each padded to 4 bytes so that the views after it stay aligned. Each texture's
    // bytes are held once, until they are copied into the chunk.
    std::vector<std::string> images;
    std::unordered_map<std::string, int> textureOf;  // a texture that two materials share: once
    const auto textureFor = [&](const std::string& path) {
        if (uv_.empty() || path.empty()) return -1;
        if (const auto known = textureOf.find(path); known != textureOf.end()) return known->second;
        std::string bytes = readImage(path);
        const std::string mimeType = detail::imageMimeType(bytes.substr(0, 8));
        if (mimeType.empty()) return textureOf[path] = -1;
        tinygltf::Image image;
        image.name = validUtf8(std::filesystem::path(path).filename().string());
        image.mimeType = mimeType;
        image.bufferView = place(bytes.size());
        const size_t pad = (4 - bytes.size() % 4) % 4;
        bytes.append(pad, '\0');
        offset += pad;
        images.push_back(std::move(bytes));
        m.images.push_back(image);
        if (m.samplers.empty()) m.samplers.emplace_back();  // repeat, the viewer's filters
        tinygltf::Texture t;
        t.sampler = 0;
        t.source = static_cast<int>(m.images.size()) - 1;
        m.textures.push_back(t);
        return textureOf[path] = static_cast<int>(m.textures.size()) - 1;
    };
    bool transformed = false;  // a texture has KHR_texture_transform
    for (const ObjMaterial& obj : usedMaterials_) {
        const int colour = textureFor(obj.texture);
        m.materials.push_back(gltfMaterial(obj, colour, textureFor(obj.normalTexture)));
        const auto& material = m.materials.back();
        transformed = transformed ||
                      !material.pbrMetallicRoughness.baseColorTexture.extensions.empty() ||
                      !material.normalTexture.extensions.empty();
    }
    if (transformed) m.extensionsUsed.push_back("KHR_texture_transform");
    std::vector<tinygltf::Value> targetNames;
    for (size_t k = 0; k < frames; ++k) {
        const auto& b = bounds_[k];
        const int position = addAccessor(m, place(12ull * n, TINYGLTF_TARGET_ARRAY_BUFFER),
                                         TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n,
                                         {b[0], b[1], b[2]}, {b[3], b[4], b[5]});
        const int normal = addAccessor(m, place(12ull * n, TINYGLTF_TARGET_ARRAY_BUFFER),
                                       TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
        primitive.targets.push_back({{"POSITION", position}, {"NORMAL", normal}});
        char label[32];
        std::snprintf(label, sizeof label, "frame_%04d", frames_[k]);
        targetNames.emplace_back(std::string(label));
    }
    const double tMin = frames ? *std::min_element(times_.begin(), times_.end()) : 0.0;
    const double tMax = frames ? *std::max_element(times_.begin(), times_.end()) : 0.0;
    const int timeAccessor = addAccessor(m, place(frames * 4), TINYGLTF_COMPONENT_TYPE_FLOAT,
                                         TINYGLTF_TYPE_SCALAR, frames, {tMin}, {tMax});
    // Key k sets weight k to 1 and every other to 0. Dense, though a sparse accessor would hold
    // only the ones: glTFast (Unity) skips accessors without a bufferView and loses the animation.
    const int weightAccessor =
        addAccessor(m, place(4 * frames * frames), TINYGLTF_COMPONENT_TYPE_FLOAT,
                    TINYGLTF_TYPE_SCALAR, frames * frames);

    std::vector<tinygltf::Primitive> primitives;
    size_t first = 0;
    for (const auto& [material, count] :
         groups_.empty() ? std::vector<std::pair<int, size_t>>{{-1, triangles.size() / 3}}
                         : groups_) {
        tinygltf::Primitive p = primitive;
        p.indices = addAccessor(m, triangleView, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                TINYGLTF_TYPE_SCALAR, 3 * count);
        m.accessors[p.indices].byteOffset = 12 * first;
        p.material = material;
        primitives.push_back(std::move(p));
        first += count;
    }
    // Names from files may not be UTF-8 (a Latin-1 file name); tinygltf's JSON would throw.
    addAnimatedMesh(m, validUtf8(name_), placement_, std::move(primitives), std::move(targetNames),
                    timeAccessor, weightAccessor);
    const std::string json = glbJson(m, offset);
    // append() estimated the JSON; this is the file's length as written, checked before it is.
    if (28 + json.size() + offset > kMaxGlbBytes) throw Error(tooLarge(path_, shape(), frames));
    size_t imageBytes = 0;
    for (const std::string& image : images) imageBytes += image.size();
    head.reserve(28 + json.size() + rest.size() * 8 + triangles.size() * 4 + uv_.size() * 4 +
                 imageBytes);
    head.append("glTF");
    appendU32(head, 2);
    appendU32(head, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + offset));
    appendU32(head, static_cast<std::uint32_t>(json.size()));
    head.append("JSON");
    head.append(json);
    appendU32(head, static_cast<std::uint32_t>(offset));
    head.append("BIN", 4);  // with its NUL: the chunk type is 0x004E4942
    appendBytes(head, rest);
    appendBytes(head, restNormals);
    appendBytes(head, triangles);
    appendBytes(head, uv_);
    for (std::string& image : images) {
        head += image;
        std::string().swap(image);  // freed as it is copied, so the textures are held once
    }
    std::FILE* spool = file_;
    file_ = nullptr;
    // The keys are written a row at a time, so memory stays at one frame's.
    writeSpooled(path_, head, spool, [&](std::FILE* out) {
        if (std::fwrite(times_.data(), 4, frames, out) != frames) return false;
        std::vector<float> row(frames, 0.0f);
        for (size_t k = 0; k < frames; ++k) {
            row[k] = 1.0f;
            if (std::fwrite(row.data(), 4, frames, out) != frames) return false;
            row[k] = 0.0f;
        }
        return true;
    });
}

}  // namespace boneless
