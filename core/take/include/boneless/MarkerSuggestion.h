#pragma once

#include <string>

#include "boneless/Alignment.h"
#include "boneless/Correspondence.h"

namespace boneless {

struct C3dTake;

struct Suggestion {
    Correspondence map;       // the partial map plus one entry per suggested marker
    Calibration calibration;  // the alignment the suggestions were made in
    int suggested = 0;
};

// Proposes a vertex for every marker of the take that `partial` does not map: the take is aligned
// onto the rest mesh from the mapped markers (at least 4, so that the similarity is
// over-determined and a wrong one shows in the residual), and each unmapped marker gets the
// nearest vertex not already carrying a marker. Its offset_mm is its distance to that vertex,
// so markers on sticks or thick suits are recorded as such. Only points classified as markers
// are considered. Throws Error naming what is missing.
Suggestion suggestMappings(const TriMesh& rest, const C3dTake& take, const Correspondence& partial);

}  // namespace boneless
