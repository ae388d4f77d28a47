#pragma once

#include <filesystem>
#include <functional>
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

// The library at `path` (absolute) as a copy of it elsewhere is written: every map statement's
// file (map_Kd, map_Bump, bump, disp, ...: what follows its options) replaced by what `name`
// gives for its absolute path, every other line as it was.
std::string relocatedLibrary(const std::string& path,
                             const std::function<std::string(const std::string&)>& name);

// Where `path` is as the system finds it, absolute: its folder's links and ".." resolved in
// turn, as opening it resolves them ("lnk/../mats" is beside lnk's target, not beside lnk, where
// a textual ".." put it), and the part that does not exist yet normalised as text. The file's own
// name is kept: a library that is itself a link is named as the OBJ names it.
std::filesystem::path resolvedPath(const std::filesystem::path& path);

// "image/png" or "image/jpeg" by the file's signature (its first bytes), empty for anything else.
std::string imageMimeType(const std::string& head);

}  // namespace boneless::detail
