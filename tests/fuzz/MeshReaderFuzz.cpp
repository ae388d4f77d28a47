// libFuzzer target for the PLY, OFF and STL readers (OpenMesh behind the project's precheck).
// The first byte picks the format so one corpus covers all three.

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <cstdlib>

#include "FuzzFile.h"
#include "FuzzSeeds.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"

// Seeds: each seed mesh in each format, ascii and binary, as OpenMesh's writers make them
// (the project reads these formats through OpenMesh and writes none of them).
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
    const std::string dir = fuzzseeds::seedDir(argc, argv);
    if (dir.empty()) return 0;
    using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
    std::filesystem::create_directories(dir);
    int n = 0;
    for (const auto& m : fuzzseeds::seedMeshes()) {
        Mesh mesh;
        std::vector<Mesh::VertexHandle> vs;
        for (int i = 0; i < m.V.rows(); ++i)
            vs.push_back(mesh.add_vertex(Mesh::Point(m.V(i, 0), m.V(i, 1), m.V(i, 2))));
        for (int f = 0; f < m.F.rows(); ++f)
            mesh.add_face(vs[m.F(f, 0)], vs[m.F(f, 1)], vs[m.F(f, 2)]);
        const char selector[] = {0, 1, 2};  // ply, off, stl: the target's first byte
        for (int k = 0; k < 3; ++k)
            for (bool binary : {false, true}) {
                static const char* const ext[] = {"ply", "off", "stl"};
                const std::string path = (std::filesystem::path(dir) / "tmp.").string() + ext[k];
                OpenMesh::IO::Options o;
                if (binary) o += OpenMesh::IO::Options::Binary;
                if (!OpenMesh::IO::write_mesh(mesh, path, o)) std::abort();
                fuzzseeds::save(dir, "mesh" + std::to_string(n) + (binary ? "-bin." : ".") + ext[k],
                                std::string(1, selector[k]) + fuzzseeds::slurp(path));
                std::filesystem::remove(path);
            }
        ++n;
    }
    fuzzseeds::done(dir);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace boneless;
    if (size == 0) return 0;
    static const char* const kExt[] = {"ply", "off", "stl"};
    const std::string path = fuzzInputFile(data + 1, size - 1, kExt[data[0] % 3]);
    try {
        const MeshReadResult r = readMesh(path);
        if (r.sourceVertexIndex.size() != std::size_t(r.mesh.vertexCount())) std::abort();
        if (r.sourceFaceIndex.size() != std::size_t(r.mesh.faceCount())) std::abort();
    } catch (const MeshError&) {
    }
    return 0;
}
