#pragma once

#include <string>
#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

struct MeshReadOptions {
    // OBJ only: read only the faces of this "g"/"o" group; empty = the whole file.
    std::string group;
};

// What readMesh found besides the mesh. Indices in messages are 0-based (vertex 0 is the file's
// first vertex, also in OBJ); line numbers are 1-based.
struct MeshReadResult {
    TriMesh mesh;
    // Things a user may want to know but that do not stop the mesh from being used: boundaries,
    // several components, zero-area faces, isolated vertices, dropped faces, reader remarks.
    std::vector<std::string> warnings;

    int sourceVertexCount = 0;           // vertices in the file
    std::vector<int> sourceVertexIndex;  // mesh vertex i is file vertex sourceVertexIndex[i]
    std::vector<int> sourceFaceIndex;    // mesh triangle t comes from file face sourceFaceIndex[t]
    int sourceFaceCount = 0;             // faces read (of the selected group)
    int polygonsTriangulated = 0;        // file faces with more than three corners
    int droppedFaces = 0;                // faces with a repeated vertex index
    int weldedVertices = 0;              // copies welded to another vertex (TriMesh::weldedTo)

    int boundaryEdges = 0;
    int boundaryLoops = 0;
    int components = 0;  // connected through faces; isolated vertices are not counted
    int isolatedVertices = 0;
    int zeroAreaFaces = 0;
};

// Reads OBJ, PLY (ascii/binary), OFF and STL (ascii/binary) into a validated, manifold,
// consistently oriented triangle mesh; throws MeshError (file, what, where) for anything unusable.
//
// Vertex order: the whole-file mesh keeps the file's vertices in file order, isolated ones too.
// With options.group, the mesh has the vertices used by that group's faces, in file order.
// STL stores no shared vertices: OpenMesh merges corners with bitwise-equal positions, so vertex i
// is the i-th distinct position in the order of first appearance (triangle by triangle, corner by
// corner), and triangles whose corners merge are dropped (reported as a warning).
// Copies of a vertex at one position (a file split at its UV seams) are welded for F: see
// TriMesh::weldedTo; the vertex count and order stay the file's.
// Binary OFF and STL go through OpenMesh, which hands over float positions. OBJ, PLY and text OFF
// are parsed here, in double precision.
MeshReadResult readMesh(const std::string& path, const MeshReadOptions& options = {});

struct ObjGroup {
    std::string name;
    int vertices = 0;  // distinct vertices its faces use: readMesh(path, {name})'s vertex count
};

// The OBJ file's "g" and "o" groups in order of first appearance, with their sizes (for a group
// chooser). Empty for files without groups and for other formats; throws MeshError if an OBJ
// cannot be read.
std::vector<ObjGroup> objGroups(const std::string& path);

}  // namespace boneless
