#pragma once

#include <functional>
#include <ostream>
#include <string>

#include "boneless/TriMesh.h"

namespace boneless {

// Writes `positions` (#V by 3) as an OBJ file, vertex order kept, full double precision (the
// shortest digits that read back to the same numbers), with `source`'s polygons, texture
// coordinates and materials when given (the mesh's `sourceFaces`; its material libraries are
// named relative to the file's folder, as given: withLibraryCopies makes them nameable), else with
// `faces` (#F by 3). The file appears atomically: it is written under a temporary name and renamed,
// so no reader ever sees half a frame. Throws Error naming the file when it cannot be written.
void writeObj(const std::string& path, const Positions& positions, const Faces& faces,
              const std::string& comment = {}, const SourceFaces* source = nullptr);
// The text writeObj writes to `path` (which names the material libraries relative to its folder).
std::string objText(const std::string& path, const Positions& positions, const Faces& faces,
                    const std::string& comment = {}, const SourceFaces* source = nullptr);

// `source` with the material libraries that OBJ files written into `folder` can name: the
// specification's mtllib takes names separated by whitespace, so a library whose path from the
// folder holds whitespace ("../src dir/a.mtl", two files to Maya and Houdini) is copied into the
// folder under a name without it (a.mtl; "my mat.mtl" as my_mat.mtl), its map statements
// naming their textures from there (copied beside it too where that path holds whitespace). A
// copy already there is used again; a file of that name that holds something else is left and
// the next free name taken (a_2.mtl). Throws Error naming a copy that cannot be written.
SourceFaces withLibraryCopies(const SourceFaces& source, const std::string& folder);

// Writes `contents` to `path` through a temporary file (temporaryFor) and a rename: a write that
// fails leaves the file `path` was and no temporary. Throws Error naming `path` and the system's
// reason.
void writeFileAtomically(const std::string& path, const std::string& contents);
// The same for contents too long to hold at once (a take's CSV): `write` puts them on the stream.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);
// Throws the Error writeFileAtomically would when `path` cannot be written (its folder missing or
// read-only), by creating and removing its temporary: asked before a long computation whose
// result goes there.
void checkWritable(const std::string& path);

}  // namespace boneless
