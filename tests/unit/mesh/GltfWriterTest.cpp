#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "TestFiles.h"
#include "TestMeshes.h"
#include "boneless/Error.h"
#include "boneless/GltfWriter.h"
#include "boneless/MeshReader.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

// An accessor's floats as tinygltf read them (tightly packed, as GltfWriter writes them).
std::vector<float> floats(const tinygltf::Model& m, int accessor) {
    const tinygltf::Accessor& a = m.accessors[accessor];
    const tinygltf::BufferView& v = m.bufferViews[a.bufferView];
    const int components = a.type == TINYGLTF_TYPE_VEC3 ? 3 : a.type == TINYGLTF_TYPE_VEC2 ? 2 : 1;
    std::vector<float> out(a.count * components);
    std::memcpy(out.data(), m.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset,
                out.size() * 4);
    return out;
}

tinygltf::Model load(const std::string& path) {
    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    EXPECT_TRUE(loader.LoadBinaryFromFile(&m, &error, &warning, path)) << error << warning;
    return m;
}

}  // namespace

TEST(GltfExport, EachFrameIsTheRestMeshPlusItsMorphTargetKeyedAtItsTime) {
    const fs::path dir = freshTestDir("glb");
    const std::string path = (dir / "sphere.glb").string();
    const TriMesh mesh = icosphere(1);
    Positions moved = mesh.V;
    moved.col(0).array() += 3.0;
    const std::vector<Positions> frames = {mesh.V, 1.5 * mesh.V, moved};
    {
        GltfWriter writer(path, mesh, "sphere");
        for (size_t k = 0; k < frames.size(); ++k)
            writer.append(static_cast<int>(k) + 4, 0.1 * (k + 4), frames[k]);
        EXPECT_FALSE(fs::exists(path));
        writer.finish();
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
    const tinygltf::Model m = load(path);
    ASSERT_EQ(m.meshes.size(), 1u);
    const tinygltf::Primitive& p = m.meshes[0].primitives[0];
    const std::vector<float> rest = floats(m, p.attributes.at("POSITION"));
    ASSERT_EQ(rest.size(), 3u * mesh.vertexCount());  // one glTF vertex per mesh vertex
    ASSERT_EQ(p.targets.size(), frames.size());
    // Named by the frame numbers given (the take's), not by their order in the file.
    const tinygltf::Value& names = m.meshes[0].extras.Get("targetNames");
    ASSERT_EQ(names.ArrayLen(), frames.size());
    for (size_t k = 0; k < frames.size(); ++k)
        EXPECT_EQ(names.Get(k).Get<std::string>(), "frame_000" + std::to_string(k + 4));
    for (size_t k = 0; k < frames.size(); ++k) {
        const std::vector<float> offset = floats(m, p.targets[k].at("POSITION"));
        double worst = 0;
        for (int v = 0; v < mesh.vertexCount(); ++v)
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst,
                                 std::abs(rest[3 * v + c] + offset[3 * v + c] - frames[k](v, c)));
        EXPECT_LT(worst, 1e-5) << "frame " << k;
    }
    const tinygltf::Accessor& indices = m.accessors[p.indices];
    EXPECT_EQ(indices.count, 3u * mesh.F.rows());

    ASSERT_EQ(m.animations.size(), 1u);
    const tinygltf::AnimationSampler& s = m.animations[0].samplers[0];
    EXPECT_EQ(s.interpolation, "LINEAR");
    EXPECT_EQ(m.animations[0].channels[0].target_path, "weights");
    const std::vector<float> times = floats(m, s.input);
    ASSERT_EQ(times.size(), 3u);
    EXPECT_FLOAT_EQ(times[0], 0.4f);
    EXPECT_FLOAT_EQ(times[2], 0.6f);
    // The weight keys: frames² values, one row of weights a key.
    EXPECT_EQ(m.accessors[s.output].count, 9u);
}

TEST(GltfExport, TextureCoordinatesGoWithTheMeshSplitAtTheirSeams) {
    const fs::path dir = freshTestDir("glb-uv");
    // Two quads side by side; the middle edge is a UV seam: each quad has its own island.
    std::ofstream(dir / "strip.obj") << "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n"
                                        "vt 0 0\nvt 0.4 0\nvt 0.4 1\nvt 0 1\n"
                                        "vt 0.6 0\nvt 1 0\nvt 1 1\nvt 0.6 1\n"
                                        "f 1/1 2/2 5/3 4/4\nf 2/5 3/6 6/7 5/8\n";
    const TriMesh strip = readMesh((dir / "strip.obj").string()).mesh;
    ASSERT_NE(strip.sourceFaces, nullptr);
    Positions posed = strip.V;
    posed.col(2) = posed.col(0).cwiseAbs2();  // bent along x: every vertex moves differently
    const std::string path = (dir / "strip.glb").string();
    {
        GltfWriter writer(path, strip, "strip");
        writer.append(0, 0.0, posed);
        writer.finish();
    }
    const tinygltf::Model m = load(path);
    const tinygltf::Primitive& p = m.meshes[0].primitives[0];
    ASSERT_TRUE(p.attributes.count("TEXCOORD_0"));
    const std::vector<float> rest = floats(m, p.attributes.at("POSITION"));
    const std::vector<float> uv = floats(m, p.attributes.at("TEXCOORD_0"));
    const std::vector<float> offset = floats(m, p.targets[0].at("POSITION"));
    ASSERT_EQ(rest.size(), 3u * 8);  // the seam's two vertices, once on each side
    ASSERT_EQ(uv.size(), 2u * 8);
    for (int g = 0; g < 8; ++g) {
        const double x = rest[3 * g], y = rest[3 * g + 1];
        // The vertex's island: left of the seam u <= 0.4, right u >= 0.6; glTF's v runs down.
        const double u = uv[2 * g], v = 1.0 - uv[2 * g + 1];
        EXPECT_FLOAT_EQ(v, y) << g;
        if (x == 0 || (x == 1 && u < 0.5))
            EXPECT_FLOAT_EQ(u, 0.4 * x) << g;
        else
            EXPECT_FLOAT_EQ(u, 0.6 + 0.4 * (x - 1)) << g;
        EXPECT_FLOAT_EQ(rest[3 * g + 2] + offset[3 * g + 2], x * x) << g;  // its vertex's motion
    }
}

TEST(GltfExport, MaterialsBecomePrimitivesWithTheirColourAndEmbeddedTexture) {
    const fs::path dir = freshTestDir("glb-materials");
    std::ofstream(dir / "paint.png", std::ios::binary) << twoByTwoPng();
    std::ofstream(dir / "bumps.png", std::ios::binary) << twoByTwoPng() + "tail";
    std::ofstream(dir / "strip.mtl") << "newmtl painted\nKd 0.3 0.3 0.3\nmap_Kd paint.png\n"
                                        "Ns 250\nmap_Bump -bm 0.5 -s 3 bumps.png\n"
                                        "newmtl tinted\nKd 0.2 0.4 0.6\nd 0.5\n"
                                        "newmtl repainted\nmap_Kd -s 2 2 1 -o 0.5 0.25 0 "
                                        "./paint.png\n";
    // Six quads in a row: the first without a material; "tinted" on the second and again on
    // the fourth, so its triangles are not together in the file; two materials share a texture;
    // a bare "usemtl" before the last keeps "repainted" on it, as Blender's OBJ importer does.
    std::string obj = "mtllib strip.mtl\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    for (int x = 0; x <= 6; ++x)
        obj += "v " + std::to_string(x) + " 0 0\nv " + std::to_string(x) + " 1 0\n";
    const char* material[6] = {nullptr, "tinted", "painted", "tinted", "repainted", ""};
    for (int q = 0; q < 6; ++q) {
        if (material[q]) obj += std::string("usemtl ") + material[q] + "\n";
        const int a = 2 * q + 1;  // bottom-left; top-left is a + 1
        obj += "f " + std::to_string(a) + "/1 " + std::to_string(a + 2) + "/2 " +
               std::to_string(a + 3) + "/3 " + std::to_string(a + 1) + "/4\n";
    }
    std::ofstream(dir / "strip.obj") << obj;
    const TriMesh strip = readMesh((dir / "strip.obj").string()).mesh;
    const std::string path = (dir / "strip.glb").string();
    {
        GltfWriter writer(path, strip, "strip");
        writer.append(0, 0.0, strip.V);
        writer.append(1, 0.1, 2.0 * strip.V);
        writer.finish();
    }
    const tinygltf::Model m = load(path);
    ASSERT_EQ(m.materials.size(), 3u);  // in order of first use
    EXPECT_EQ(m.materials[0].name, "tinted");
    EXPECT_EQ(m.materials[0].pbrMetallicRoughness.baseColorFactor,
              (std::vector<double>{0.2, 0.4, 0.6, 0.5}));
    EXPECT_EQ(m.materials[0].alphaMode, "BLEND");
    EXPECT_EQ(m.materials[0].pbrMetallicRoughness.baseColorTexture.index, -1);
    EXPECT_EQ(m.materials[1].name, "painted");
    EXPECT_EQ(m.materials[1].alphaMode, "OPAQUE");
    EXPECT_EQ(m.materials[1].pbrMetallicRoughness.metallicFactor, 0.0);
    EXPECT_DOUBLE_EQ(m.materials[1].pbrMetallicRoughness.roughnessFactor, 0.5);
    EXPECT_EQ(m.materials[0].pbrMetallicRoughness.roughnessFactor, 1.0);  // no Ns
    EXPECT_EQ(m.materials[1].normalTexture.scale, 0.5);
    EXPECT_EQ(m.materials[0].normalTexture.index, -1);
    const int texture = m.materials[1].pbrMetallicRoughness.baseColorTexture.index;
    ASSERT_GE(texture, 0);
    EXPECT_EQ(m.materials[2].pbrMetallicRoughness.baseColorTexture.index, texture);
    // Its -s and -o, which the OBJ frames keep, as KHR_texture_transform: in glTF's v, which runs
    // down the image, the offset is 1 - 2 - 0.25. Without them the glb showed another tiling.
    EXPECT_TRUE(m.materials[1].pbrMetallicRoughness.baseColorTexture.extensions.empty());
    const tinygltf::Value& transform =
        m.materials[2].pbrMetallicRoughness.baseColorTexture.extensions.at("KHR_texture_transform");
    EXPECT_EQ(transform.Get("offset").Get(0).GetNumberAsDouble(), 0.5);
    EXPECT_EQ(transform.Get("offset").Get(1).GetNumberAsDouble(), -1.25);
    EXPECT_EQ(transform.Get("scale").Get(0).GetNumberAsDouble(), 2.0);
    EXPECT_EQ(transform.Get("scale").Get(1).GetNumberAsDouble(), 2.0);
    EXPECT_EQ(m.extensionsUsed, std::vector<std::string>{"KHR_texture_transform"});
    const tinygltf::Value& bumpTransform =
        m.materials[1].normalTexture.extensions.at("KHR_texture_transform");
    EXPECT_EQ(bumpTransform.Get("scale").Get(0).GetNumberAsDouble(), 3.0);
    EXPECT_EQ(bumpTransform.Get("scale").Get(1).GetNumberAsDouble(), 1.0);  // -s u alone
    EXPECT_EQ(bumpTransform.Get("offset").Get(1).GetNumberAsDouble(), 0.0);
    const int bumps = m.materials[1].normalTexture.index;
    ASSERT_GE(bumps, 0);
    EXPECT_NE(bumps, texture);
    EXPECT_EQ(m.materials[2].normalTexture.index, -1);
    EXPECT_EQ(m.images[m.textures[bumps].source].name, "bumps.png");
    ASSERT_EQ(m.images.size(), 2u);  // the shared colour texture once, and the normal map
    const tinygltf::Image& image = m.images[m.textures[texture].source];
    EXPECT_EQ(image.mimeType, "image/png");
    EXPECT_EQ(image.width, 2);  // tinygltf decoded it
    const tinygltf::BufferView& view = m.bufferViews[image.bufferView];
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(m.buffers[0].data.data()) + view.byteOffset,
                          view.byteLength),
              twoByTwoPng());

    // One primitive per material (none first), sharing the vertices and the morph targets.
    const std::vector<tinygltf::Primitive>& p = m.meshes[0].primitives;
    ASSERT_EQ(p.size(), 4u);
    const int expectedMaterial[4] = {-1, 0, 1, 2};
    const std::set<int> expectedQuads[4] = {{0}, {1, 3}, {2}, {4, 5}};
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(p[k].material, expectedMaterial[k]);
        EXPECT_EQ(p[k].attributes.at("POSITION"), p[0].attributes.at("POSITION"));
        ASSERT_EQ(p[k].targets.size(), 2u);
        EXPECT_EQ(p[k].targets[1].at("POSITION"), p[0].targets[1].at("POSITION"));
        const tinygltf::Accessor& a = m.accessors[p[k].indices];
        const std::vector<float> rest = floats(m, p[k].attributes.at("POSITION"));
        const tinygltf::BufferView& v = m.bufferViews[a.bufferView];
        const auto* index = reinterpret_cast<const std::uint32_t*>(m.buffers[0].data.data() +
                                                                   v.byteOffset + a.byteOffset);
        std::set<int> quads;  // by each triangle's centre
        for (size_t t = 0; t < a.count / 3; ++t)
            quads.insert(static_cast<int>(
                (rest[3 * index[3 * t]] + rest[3 * index[3 * t + 1]] + rest[3 * index[3 * t + 2]]) /
                3));
        EXPECT_EQ(quads, expectedQuads[k]) << "primitive " << k;
        EXPECT_EQ(a.count, 6 * expectedQuads[k].size()) << "primitive " << k;
    }
}

TEST(GltfExport, EachTextureLandsWholeInItsOwnAlignedView) {
    const fs::path dir = freshTestDir("glb-two-textures");
    // 75 and 79 bytes (a decoder reads up to IEND), so each is padded and they differ.
    const std::map<std::string, std::string> bytes{{"one.png", twoByTwoPng()},
                                                   {"two.png", twoByTwoPng() + "tail"}};
    for (const auto& [name, content] : bytes)
        std::ofstream(dir / name, std::ios::binary) << content;
    std::ofstream(dir / "pair.mtl") << "newmtl a\nmap_Kd one.png\nnewmtl b\nmap_Kd two.png\n";
    std::ofstream(dir / "pair.obj") << "mtllib pair.mtl\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                       "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 4/4\n";
    const TriMesh pair = readMesh((dir / "pair.obj").string()).mesh;
    const std::string path = (dir / "pair.glb").string();
    {
        GltfWriter writer(path, pair, "pair");
        writer.append(0, 0.0, pair.V);
        writer.finish();
    }
    const tinygltf::Model m = load(path);
    ASSERT_EQ(m.images.size(), 2u);
    for (const tinygltf::Image& image : m.images) {
        const tinygltf::BufferView& view = m.bufferViews[image.bufferView];
        EXPECT_EQ(view.byteOffset % 4, 0u) << image.name;
        EXPECT_EQ(
            std::string(reinterpret_cast<const char*>(m.buffers[0].data.data()) + view.byteOffset,
                        view.byteLength),
            bytes.at(image.name))
            << image.name;
    }
    EXPECT_EQ(m.meshes[0].primitives.size(), 2u);
}

TEST(GltfExport, AnAbandonedFileLeavesNothingBehind) {
    const fs::path dir = freshTestDir("glb-abandoned");
    const TriMesh mesh = icosphere(0);
    {
        GltfWriter writer((dir / "x.glb").string(), mesh, "x");
        writer.append(0, 0.0, mesh.V);
        EXPECT_THROW(writer.append(1, 0.1, mesh.V.topRows(3)), Error);  // wrong vertex count
    }
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(GltfExport, TheNodePlacesTheMeshsOwnCoordinatesInGltfsFrame) {
    const fs::path dir = freshTestDir("glb-placement");
    const std::string path = (dir / "sphere.glb").string();
    const TriMesh mesh = icosphere(1);
    GltfPlacement placement;  // a Z-up mesh in decimetres
    placement.turn = Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX()).toRotationMatrix();
    placement.metresPerUnit = 0.1;
    {
        GltfWriter writer(path, mesh, "sphere", placement);
        writer.append(0, 0.0, mesh.V);
        writer.finish();
    }
    const tinygltf::Model m = load(path);
    ASSERT_EQ(m.nodes.size(), 1u);
    const tinygltf::Node& node = m.nodes[0];
    ASSERT_EQ(node.rotation.size(), 4u);
    const Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1],
                               node.rotation[2]);
    EXPECT_LT((q * Vec3::UnitZ() - Vec3::UnitY()).norm(), 1e-12);  // the mesh's up is glTF's
    EXPECT_EQ(node.scale, (std::vector<double>{0.1, 0.1, 0.1}));
    const std::vector<float> rest = floats(m, m.meshes[0].primitives[0].attributes.at("POSITION"));
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(rest[c], float(mesh.V(0, c)));
}

// glTFast (Unity) skips an accessor without a bufferView and then reads its empty slot, so a
// sparse accessor for the weight keys left Unity with no animation (glTFast issue #768).
TEST(GltfExport, TheWeightKeysAreDenseIdentityRowsThatUnityImportersRead) {
    const fs::path dir = freshTestDir("glb-dense-keys");
    const std::string path = (dir / "sphere.glb").string();
    const TriMesh mesh = icosphere(0);
    const int frames = 4;
    {
        GltfWriter writer(path, mesh, "sphere");
        for (int k = 0; k < frames; ++k) writer.append(k, 0.1 * k, (1.0 + 0.1 * k) * mesh.V);
        writer.finish();
    }
    const tinygltf::Model m = load(path);
    const tinygltf::Accessor& weights = m.accessors[m.animations[0].samplers[0].output];
    EXPECT_FALSE(weights.sparse.isSparse);
    ASSERT_GE(weights.bufferView, 0);
    ASSERT_EQ(weights.count, size_t(frames * frames));
    const std::vector<float> keys = floats(m, m.animations[0].samplers[0].output);
    for (int k = 0; k < frames; ++k)
        for (int t = 0; t < frames; ++t)
            EXPECT_EQ(keys[k * frames + t], k == t ? 1.0f : 0.0f) << "key " << k << " target " << t;
}

// The dense keys take frames² × 4 bytes: past about 32,000 frames no .glb can hold them, and
// that is said before solving, with the file, the frame count and how many frames would fit.
TEST(GltfExport, AGlbTooLargeForTheContainerIsRefusedNamingTheFramesThatFit) {
    const TriMesh mesh = icosphere(0);
    EXPECT_NO_THROW(checkGlbFits("out/w.glb", mesh, 30000));
    const std::string error = errorOf([&] { checkGlbFits("out/w.glb", mesh, 40000); });
    EXPECT_NE(error.find("out/w.glb: 40000 frames"), std::string::npos) << error;
    EXPECT_NE(error.find("--frames"), std::string::npos) << error;
    EXPECT_NE(error.find("at most 326"), std::string::npos) << error;
}

// Unity's blend shapes change the shading only by their normal offsets, and glTFast computes
// normals once for the base mesh: without NORMAL the body moved in its rest pose's shading.
TEST(GltfExport, EachFramesNormalsAreTheBaseNormalsPlusItsNormalTarget) {
    const fs::path dir = freshTestDir("glb-normals");
    // Two quads with a UV seam between them: the seam's vertices are two glTF vertices each.
    std::ofstream(dir / "strip.obj") << "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n"
                                        "vt 0 0\nvt 0.4 0\nvt 0.4 1\nvt 0 1\n"
                                        "vt 0.6 0\nvt 1 0\nvt 1 1\nvt 0.6 1\n"
                                        "f 1/1 2/2 5/3 4/4\nf 2/5 3/6 6/7 5/8\n";
    const TriMesh strip = readMesh((dir / "strip.obj").string()).mesh;
    Positions bent = strip.V;
    bent.col(2) = bent.col(0).cwiseAbs2();  // z = x²: each column of vertices tilts differently
    const std::string path = (dir / "strip.glb").string();
    {
        GltfWriter writer(path, strip, "strip");
        writer.append(0, 0.0, strip.V);
        writer.append(1, 0.1, bent);
        writer.finish();
    }
    // Area-weighted vertex normals of the mesh's triangles, as the test computes them.
    const auto normals = [&](const Positions& V) {
        Positions n = Positions::Zero(V.rows(), 3);
        for (int t = 0; t < strip.F.rows(); ++t) {
            const Vec3 a = V.row(strip.F(t, 0)), b = V.row(strip.F(t, 1)), c = V.row(strip.F(t, 2));
            for (int k = 0; k < 3; ++k) n.row(strip.F(t, k)) += (b - a).cross(c - a);
        }
        n.rowwise().normalize();
        return n;
    };
    const Positions flat = normals(strip.V), posed = normals(bent);
    const tinygltf::Model m = load(path);
    const tinygltf::Primitive& p = m.meshes[0].primitives[0];
    ASSERT_TRUE(p.attributes.count("NORMAL"));
    ASSERT_EQ(p.targets.size(), 2u);
    ASSERT_TRUE(p.targets[1].count("NORMAL"));
    const std::vector<float> rest = floats(m, p.attributes.at("POSITION"));
    const std::vector<float> base = floats(m, p.attributes.at("NORMAL"));
    const std::vector<float> delta = floats(m, p.targets[1].at("NORMAL"));
    ASSERT_EQ(base.size(), 3u * 8);
    for (int g = 0; g < 8; ++g) {
        // The mesh vertex this glTF vertex is, by its rest position (x, y on the unit grid).
        const int v = static_cast<int>(rest[3 * g]) + 3 * static_cast<int>(rest[3 * g + 1]);
        EXPECT_NEAR(Vec3(base[3 * g], base[3 * g + 1], base[3 * g + 2]).norm(), 1.0, 1e-6) << g;
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(base[3 * g + c], flat(v, c), 1e-6) << g;
            EXPECT_NEAR(base[3 * g + c] + delta[3 * g + c], posed(v, c), 1e-6) << g;
        }
    }
    EXPECT_GT(std::abs(delta[0]), 0.1);  // the bend tilts the normals
}
