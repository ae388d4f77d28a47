#pragma once

#include <optional>
#include <string>
#include <vector>

#include "PolygonSoup.h"

namespace boneless::detail {

// What a quick pass over an OFF/PLY/STL file learned before OpenMesh reads it. OpenMesh's text
// parsers keep going after a bad number or a missing line and deliver stale or uninitialised
// values, so this pass rejects malformed and non-finite numbers itself (with line numbers) and
// knows the counts the file announces. Throws MeshError; unknown extensions included.
struct Precheck {
    bool stl = false;
    long long triangles = -1;         // STL: triangles in the file
    long long declaredVertices = -1;  // OFF/PLY header counts (-1: not known)
    long long declaredFaces = -1;
    // Text OFF and PLY, read here in full from the values this pass checked. OpenMesh's OFF
    // reader takes neither comments nor "OFF nv nf ne", and read from a stream it parses with the
    // header flags (binary, colours, normals) of the previous file it opened; it only reads binary
    // OFF. Its PLY reader misread valid files (PlyPrecheck.cpp).
    std::optional<PolygonSoup> soup;
};

Precheck precheckForOpenMesh(const std::string& path);

// Lower-case extension without the dot ("" if none).
std::string lowerExtension(const std::string& path);

}  // namespace boneless::detail
