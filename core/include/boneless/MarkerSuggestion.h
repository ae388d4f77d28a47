#pragma once

#include <string>

#include "boneless/Alignment.h"
#include "boneless/Correspondence.h"

namespace boneless {

struct C3dTake;

struct Suggestion {
    Correspondence map;       // the partial map plus one entry per suggested marker
    Calibration calibration;  // the alignment the suggestions were made in
    Positions fitted;         // the rest mesh fitted to the take at fittedFrame
    int fittedFrame = -1;     // the frame the fit comes nearest the unmapped markers
    int suggested = 0;
    int needsReview = 0;  // suggested entries marked "needs_review": true
};

// Proposes a vertex for every marker of the take that `partial` does not map. The take is
// aligned onto the rest mesh from the mapped markers (at least 4, so that the similarity is
// over-determined and a wrong one shows in the residual); the mesh is then fitted to the take by
// the engine, pulled by the mapped markers, at the calibration frame and at frames spread over
// the take (a rigid alignment cannot bring a T-posed mesh onto an actor whose arms are down), and
// each unmapped marker gets the free vertex that stays nearest it over those fits, the better
// fitted frames counting more. An entry's offset_mm is its distance to that vertex on the best
// fitted frame; it is marked "suggested": true, and "needs_review": true with a "review_reason"
// when it lies far from the mesh there, when a vertex on another part of the body (left or
// right) follows the marker about as closely, or when the marker is not seen there. Only points
// classified as markers are considered. Throws Error naming what is missing.
Suggestion suggestMappings(const TriMesh& rest, const C3dTake& take, const Correspondence& partial);

// How far (mm, on the rest mesh, using the alignment's scale) each of `suggestion`'s suggested
// markers lies from the same label's vertex in `reference`; labels `reference` lacks are skipped.
struct SuggestionCheck {
    int compared = 0;
    int within = 0;  // at most `toleranceMm` away
    double medianMm = 0;
};
SuggestionCheck checkSuggestion(const TriMesh& rest, const C3dTake& take,
                                const Suggestion& suggestion, const Correspondence& reference,
                                double toleranceMm);

}  // namespace boneless
