#pragma once

#include "boneless/MarkerSuggestion.h"

namespace boneless {

// How near a suggestion's proposals land to a map known to be right: for each suggested entry
// whose label the reference maps, the distance on the rest mesh between the two surface points,
// in millimetres of the take (through the suggestion's alignment scale).
struct SuggestionCheck {
    int compared = 0;
    int within = 0;  // at most toleranceMm away
    double medianMm = 0;
    std::vector<std::pair<std::string, double>> distancesMm;  // label, distance; entry order
};
SuggestionCheck checkSuggestion(const TriMesh& rest, const C3dTake& take,
                                const Suggestion& suggestion, const Correspondence& reference,
                                double toleranceMm);

}  // namespace boneless
