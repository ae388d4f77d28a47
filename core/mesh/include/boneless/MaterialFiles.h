#pragma once

#include <string>
#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// The files a glb written from `faces` is made of besides the OBJ: its material libraries and
// every texture they name (absolute paths), found or not, since one that appears later would be
// embedded. A batch run fingerprints them to tell a glb solved from other materials.
std::vector<std::string> materialFiles(const SourceFaces& faces);

}  // namespace boneless
