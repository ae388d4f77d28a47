#pragma once

#include <string>

#include "boneless/TriMesh.h"

namespace boneless {

// Writes `positions` (#V by 3) as an OBJ file, vertex order kept, full double precision (the
// shortest digits that read back to the same numbers), with `source`'s polygons, texture
// coordinates and materials when given (the mesh's `sourceFaces`; its material libraries are
// named relative to the file's folder), else with `faces` (#F by 3). The file appears
// atomically: it is written under a temporary name and renamed, so no reader ever sees half a
// frame. Throws Error naming the file when it cannot be written.
void writeObj(const std::string& path, const Positions& positions, const Faces& faces,
              const std::string& comment = {}, const SourceFaces* source = nullptr);

// Writes `contents` to `path` through a temporary file and a rename.
void writeFileAtomically(const std::string& path, const std::string& contents);

}  // namespace boneless
