// libFuzzer target for the OBJ reader, through readMesh as a user's file goes. Any input must
// read or raise MeshError; what reads must be a valid mesh whose bookkeeping agrees with it.

#include <cstdlib>

#include "FuzzFile.h"
#include "FuzzSeeds.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/ObjWriter.h"

// Seeds: the writer's output for two meshes, then the same with what writers of other tools
// add (groups, texture and normal indices, polygons, negative indices).
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
    const std::string dir = fuzzseeds::seedDir(argc, argv);
    if (dir.empty()) return 0;
    int n = 0;
    for (const auto& m : fuzzseeds::seedMeshes()) {
        const std::string path =
            (std::filesystem::path(dir) / ("mesh" + std::to_string(n++) + ".obj"));
        std::filesystem::create_directories(dir);
        boneless::writeObj(path, m.V, m.F, "seed");
        const std::string text = fuzzseeds::slurp(path);
        fuzzseeds::save(dir, "grouped" + std::to_string(n) + ".obj",
                        "o body\ng head\n" + text + "g tail\nf -1 -2 -3\n");
    }
    fuzzseeds::save(dir, "features.obj",
                    "mtllib a.mtl\nv 0 0 0\nv 1 0 0 1\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                    "g quad\nusemtl m\ns 1\nf 1/1/1 2/1/1 3/1/1 4/1/1\nl 1 2\n");
    fuzzseeds::done(dir);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace boneless;
    const std::string path = fuzzInputFile(data, size, "obj");
    try {
        const std::vector<ObjGroup> groups = objGroups(path);
        MeshReadOptions options;
        int groupVertices = -1;
        if (!groups.empty()) {
            options.group = groups[size % groups.size()].name;
            groupVertices = groups[size % groups.size()].vertices;
        }
        const MeshReadResult r = readMesh(path, options);
        // The chooser's count is the size of the mesh the group reads as.
        if (groupVertices >= 0 && groupVertices != r.mesh.vertexCount()) std::abort();
        if (r.sourceVertexIndex.size() != std::size_t(r.mesh.vertexCount())) std::abort();
        if (r.sourceFaceIndex.size() != std::size_t(r.mesh.faceCount())) std::abort();
        for (int v : r.sourceVertexIndex)
            if (v < 0 || v >= r.sourceVertexCount) std::abort();
    } catch (const MeshError&) {
    }
    return 0;
}
