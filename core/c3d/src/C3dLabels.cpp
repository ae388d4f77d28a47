// The points' names: POINT:LABELS (continued in LABELS2, ...) and DESCRIPTIONS.

#include "C3dTakeLayout.h"

namespace boneless::c3d_detail {

void readLabels(const C3dParameters& ps, std::size_t points, C3dTake& take, bool& latin1) {
    auto& warn = take.warnings;
    std::vector<std::string> labels = ps.continuedStrings("POINT", "LABELS");
    std::vector<std::string> descriptions = ps.continuedStrings("POINT", "DESCRIPTIONS");
    if (labels.size() < points && ps.find("POINT", "LABELS"))
        warn.push_back("POINT:LABELS holds " + std::to_string(labels.size()) + " labels for " +
                       std::to_string(points) + " points; the rest are named P<n>");
    take.points.resize(points);
    std::size_t unnamed = 0;
    for (std::size_t i = 0; i < points; ++i) {
        C3dPoint& p = take.points[i];
        if (i < labels.size()) p.label = textFromC3d(labels[i], latin1);
        if (p.label.empty()) {
            p.label = "P" + std::to_string(i + 1);
            ++unnamed;
        }
        if (i < descriptions.size()) p.description = textFromC3d(descriptions[i], latin1);
    }
    if (latin1) {
        take.textEncoding = C3dTextEncoding::Latin1;
        warn.push_back("labels, descriptions or units are not UTF-8; read as Latin-1");
    }
    if (unnamed > 0 && labels.size() >= points)
        warn.push_back(std::to_string(unnamed) + " points have empty labels; named P<n>");
    // No map entry can say which of them it means (Correspondence::resolve refuses it).
    const std::vector<std::vector<std::size_t>> shared = take.sharedLabels();
    constexpr std::size_t kListed = 10;
    for (std::size_t g = 0; g < shared.size() && g < kListed; ++g)
        warn.push_back(take.sharedLabelText(shared[g]) + "; no map can name one of them");
    if (shared.size() > kListed)
        warn.push_back(std::to_string(shared.size() - kListed) +
                       " more labels are each held by several points");
}

}  // namespace boneless::c3d_detail
