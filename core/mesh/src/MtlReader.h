#pragma once

#include <string>
#include <vector>

#include "boneless/TriMesh.h"

namespace boneless::detail {

// The materials that OBJ material libraries (.mtl files, absolute paths) define: name, diffuse
// colour, opacity and diffuse texture. Nothing here stops a mesh from loading: a library that
// cannot be read, a line that does not parse, and a texture that is missing or neither PNG nor
// JPEG (all that glTF carries) are warnings, each naming the file and line (a library that
// cannot be read: the file). With `textures`, every texture file a map statement names is added to
// it (absolute, found or not).
std::vector<ObjMaterial> readMaterialLibraries(const std::vector<std::string>& paths,
                                               std::vector<std::string>& warnings,
                                               std::vector<std::string>* textures = nullptr);

// "image/png" or "image/jpeg" by the file's signature (its first bytes), empty for anything else.
std::string imageMimeType(const std::string& head);

}  // namespace boneless::detail
