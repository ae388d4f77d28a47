#pragma once

// Whether solving a mesh fits the memory this process may use, checked before any solver is
// built: by the CLI's solve and batch, the export and the app. The estimate and its figures:
// docs/benchmarks.md, "Large meshes".

#include <string>

#include "boneless/Reconstruction.h"
#include "boneless/TriMesh.h"

namespace boneless {

// Throws Error naming the mesh file, its faces and vertices, the memory one solver of it would
// take with this method and what the process may use, when that solver would not fit.
void checkSolveFits(const TriMesh& mesh, const std::string& meshPath, SolverOptions::Method method);

}  // namespace boneless
