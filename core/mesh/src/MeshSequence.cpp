#include "boneless/MeshSequence.h"

#include <algorithm>
#include <filesystem>

#include "boneless/Error.h"
#include "boneless/MeshReader.h"

namespace boneless {

namespace {

// Polygons are triangulated by their posed shape, so frames of one quad mesh may split a quad
// differently: the file's own faces are what must match.
bool sameFaces(const TriMesh& a, const TriMesh& b) {
    if (a.sourceFaces && b.sourceFaces)
        return a.sourceFaces->start == b.sourceFaces->start &&
               a.sourceFaces->corners == b.sourceFaces->corners;
    return !a.sourceFaces && !b.sourceFaces && a.F == b.F;
}

}  // namespace

MeshSequence readMeshSequence(const std::string& directory) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_directory(directory, ec))
        throw MeshError(directory, "not a directory of mesh frames");
    MeshSequence sequence;
    for (const auto& entry : fs::directory_iterator(directory)) {
        std::string ext = entry.path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
        if (entry.is_regular_file() && ext == ".obj")
            sequence.files.push_back(entry.path().string());
    }
    if (sequence.files.empty()) throw MeshError(directory, "contains no .obj frames");
    std::sort(sequence.files.begin(), sequence.files.end());
    for (const auto& file : sequence.files) {
        TriMesh mesh = readMesh(file).mesh;
        if (sequence.frames.empty()) {
            sequence.rest = mesh;
        } else if (mesh.vertexCount() != sequence.rest.vertexCount()) {
            throw MeshError(file, "has " + std::to_string(mesh.vertexCount()) +
                                      " vertices, the first frame " +
                                      std::to_string(sequence.rest.vertexCount()));
        } else if (!sameFaces(mesh, sequence.rest)) {
            throw MeshError(file,
                            "has other faces than the first frame (" + sequence.files[0] + ")");
        }
        sequence.frames.push_back(std::move(mesh.V));
    }
    return sequence;
}

}  // namespace boneless
