#pragma once

#include <string>

#include "boneless/TriMesh.h"

namespace boneless {

// Writes `positions` (#V by 3) with `faces` as an OBJ file, vertex order kept, full double
// precision (17 significant digits, so a read gives back the same numbers). The file appears
// atomically: it is written under a temporary name and renamed, so no reader ever sees half a
// frame. Throws Error naming the file when it cannot be written.
void writeObj(const std::string& path, const Positions& positions, const Faces& faces,
              const std::string& comment = {});

// Writes `contents` to `path` through a temporary file and a rename.
void writeFileAtomically(const std::string& path, const std::string& contents);

}  // namespace boneless
