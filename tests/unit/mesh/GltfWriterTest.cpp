#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>

#include "TestMeshes.h"
#include "boneless/Error.h"
#include "boneless/GltfWriter.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

// An accessor's floats as tinygltf read them (tightly packed, as GltfWriter writes them).
std::vector<float> floats(const tinygltf::Model& m, int accessor) {
    const tinygltf::Accessor& a = m.accessors[accessor];
    const tinygltf::BufferView& v = m.bufferViews[a.bufferView];
    const int components = a.type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
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
        for (size_t k = 0; k < frames.size(); ++k) writer.append(0.1 * (k + 4), frames[k]);
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
    // The weight keys: frames² values, of which only the ones on the diagonal are stored.
    const tinygltf::Accessor& weights = m.accessors[s.output];
    EXPECT_EQ(weights.count, 9u);
    EXPECT_TRUE(weights.sparse.isSparse);
    EXPECT_EQ(weights.sparse.count, 3);
    EXPECT_EQ(weights.bufferView, -1);  // everything else is zero
}

TEST(GltfExport, AnAbandonedFileLeavesNothingBehind) {
    const fs::path dir = freshTestDir("glb-abandoned");
    const TriMesh mesh = icosphere(0);
    {
        GltfWriter writer((dir / "x.glb").string(), mesh, "x");
        writer.append(0, mesh.V);
        EXPECT_THROW(writer.append(0.1, mesh.V.topRows(3)), Error);  // wrong vertex count
    }
    EXPECT_TRUE(fs::is_empty(dir));
}
