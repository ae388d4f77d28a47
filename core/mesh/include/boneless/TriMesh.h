#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products everywhere
#include <array>
#include <memory>
#include <string>
#include <vector>

namespace boneless {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;  // #V by 3
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;         // #F by 3

// A map statement's -o and -s (offset and scale of the texture coordinates, u then v).
struct TextureTransform {
    std::array<double, 2> offset{0, 0}, scale{1, 1};
    bool identity() const {
        return offset == std::array<double, 2>{0, 0} && scale == std::array<double, 2>{1, 1};
    }
};

// A material as an OBJ library (.mtl) defines it, as far as a glTF material carries it.
struct ObjMaterial {
    std::string name;                             // "newmtl"
    std::array<double, 3> colour{0.8, 0.8, 0.8};  // "Kd", the diffuse colour
    double opacity = 1;                           // "d", or 1 − "Tr"
    double roughness = 1;  // as Blender reads "Ns": 1 − √(Ns / 1000); "illum 2" alone: 0
    std::string texture;   // "map_Kd": absolute path of a PNG or JPEG file, or empty
    TextureTransform textureTransform;  // its -o and -s
    std::string normalTexture;  // "map_Bump", "map_bump" or "bump", a normal map (as Blender)
    double normalScale = 1;     // its "-bm" strength
    TextureTransform normalTransform;  // its -o and -s
};

// The input file's own faces, for writers that give them back (OBJ frames): its polygons, their
// texture coordinates and materials, where the solver sees only triangles.
struct SourceFaces {
    int vertexCount = 0;        // of the mesh they belong to
    std::vector<int> start{0};  // polygon p's corners are corners[start[p] .. start[p + 1])
    std::vector<int> corners;   // mesh vertex indices
    std::vector<int> uvOf;      // per corner, an index into uv or -1; empty when the file has none
    std::vector<double> uv;     // 2 per texture coordinate (OBJ "vt"), those the polygons use
    std::vector<std::string> materialLibraries;  // absolute paths (OBJ "mtllib")
    // Runs of polygons by material: (first polygon, index into materialDefinitions); the
    // polygons before the first run have none.
    std::vector<std::pair<int, int>> materials;
    // What the libraries define, then a default one for each name used that none defines.
    std::vector<ObjMaterial> materialDefinitions;

    int polygonCount() const { return static_cast<int>(start.size()) - 1; }
};

// A triangle mesh as the rest of the core sees it: plain arrays, vertex i is the input file's
// vertex i, faces oriented as in the file.
struct TriMesh {
    Positions V;
    Faces F;
    // The file's polygons and texture coordinates when they are more than F (quads, UVs,
    // materials); shared, since a posed copy of the mesh has the same ones.
    std::shared_ptr<const SourceFaces> sourceFaces;
    // Per vertex, the vertex it is welded to: copies at one position (a file split at its UV
    // seams) are one vertex to F and the solve, the first in file order; a pose gives each copy
    // that vertex's position (followWelds). Empty when nothing is welded.
    std::vector<int> weldedTo;

    int vertexCount() const { return static_cast<int>(V.rows()); }
    int faceCount() const { return static_cast<int>(F.rows()); }
};

// The vertex `v` is welded to (v itself when it is no copy).
inline int weldedVertex(const TriMesh& mesh, int v) {
    return mesh.weldedTo.empty() ? v : mesh.weldedTo[v];
}
// Puts every copy of a welded vertex where that vertex is in V (#V by 3).
void followWelds(const TriMesh& mesh, Positions& V);

// Length of the diagonal of the axis-aligned bounding box (0 for an empty mesh).
double boundingBoxDiagonal(const Positions& V);
// The same over the vertices the faces F use: what tolerances scale with, since one isolated
// vertex far away would otherwise make every triangle "zero-area" and every step "still".
double boundingBoxDiagonal(const Positions& V, const Faces& F);

// Whether the triangle (a, b, c) has no area, relative to a model of bounding-box diagonal
// `diagonal`: corners on a line up to rounding count, since their angles are rounding noise.
bool zeroArea(const Vec3& a, const Vec3& b, const Vec3& c, double diagonal);

}  // namespace boneless
