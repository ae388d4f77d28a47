#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "boneless/Alignment.h"
#include "boneless/Correspondence.h"

namespace boneless {

struct C3dTake;

// One suggested marker: where it goes, and whether the user should look at it before trusting it.
struct Proposal {
    std::string label;
    int vertex = -1;
    bool needsReview = false;
    std::string reviewReason;  // why, for a person: "62 mm from the fitted mesh", ...
};

struct Suggestion {
    Correspondence map;       // the partial map plus one entry per suggested marker
    Calibration calibration;  // the alignment the suggestions were made in
    int fittedFrame = -1;     // the frame whose fit by the picks came nearest the other markers
                              // (-1, and a default calibration, when nothing was suggested)
    std::vector<Proposal> proposals;  // one per suggested entry, in the map's order
    int suggested = 0;
    int needsReview = 0;
    // Markers left unmapped because no fit comes within kUnreachableMm of them (a prop, another
    // actor), or the best fit puts their vertex farther: their labels as the take gives them
    // ("boite:1"), in the take's order.
    std::vector<std::string> offBody;
    // Markers of a subject no pick names ("B:LFHD" when the picks are A's), left unmapped.
    std::vector<std::string> otherSubjects;
    // Labels two or more points of the take share (C3dTake::sharedLabels), once each, left
    // unmapped: no entry could say which point it means, and solve refuses such an entry.
    std::vector<std::string> sharedLabels;
    bool stopped = false;  // `stop` was set: nothing was suggested, the map is the partial one
};

// Proposes a vertex for every marker of the take that `partial` does not map. The take is
// aligned onto the rest mesh from the mapped markers (at least 4, so that the similarity is
// over-determined and a wrong one shows in the residual); the rest is fitted to the actor there
// (solve's shape calibration), and the engine poses it by the mapped markers at frames spread
// over the take, keeps the fits that come nearest the other markers, and gives each unmapped
// marker the free vertex that follows it best over those fits, near the mirror image of its
// picked partner (RFWT of LFWT) when the mesh is mirrored (docs/markers.md). An entry's
// offset_mm is the picks' median offset; it is marked "suggested": true, and
// "needs_review": true with a "review_reason" when it lies far from the fitted mesh, when another
// part of the body fits it about as well, when it is named for one side (L…/R…, as the mapped pairs
// show the sides) and lands on the other, or when it is not seen on the best fit's frame. Only
// points classified as markers are considered, and one farther than kUnreachableMm from every
// vertex over the fits (a prop, another actor), or from its vertex on the best fit, gets no
// entry: Suggestion::offBody names it.
// Throws Error naming what is missing, or a mapped marker the mesh cannot reach.
// `meshUp`: the mesh's up axis, as solve's "mesh_up" gives it; none, the one the alignment puts
// nearest the take's vertical.
// `stop`: checked between the fits it scans (a window closing); once set, it returns stopped.
Suggestion suggestMappings(const TriMesh& rest, const C3dTake& take, const Correspondence& partial,
                           const std::optional<Vec3>& meshUp = std::nullopt,
                           const std::atomic<bool>* stop = nullptr);

// What `suggest` wrote on a map entry, as the user left it: "suggested": true, and
// "needs_review": true with its "review_reason" (the app clears both when the user accepts or
// moves the entry). Anything but a JSON true is no mark: a hand-edited "yes" neither counts nor
// throws.
struct SuggestionMark {
    bool suggested = false;
    bool needsReview = false;
    std::string reviewReason;  // "needs review" when the mark gives none
};
SuggestionMark suggestionMark(const MarkerMapping& entry);

// The labels of the map's entries still marked "needs_review": true, in the map's order.
std::vector<std::string> labelsToReview(const Correspondence& map);

}  // namespace boneless
