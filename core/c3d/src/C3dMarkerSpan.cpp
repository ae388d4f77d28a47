// Whether the take's markers span what a body does in the units the file states.

#include <algorithm>
#include <cmath>
#include <vector>

#include "C3dDetail.h"
#include "boneless/Text.h"

namespace boneless::c3d_detail {

namespace {

// Frames measured, as many as the vertical's check reads (C3dVertical.cpp).
constexpr std::size_t kSpanFrames = 256;
// A body spans 0.3 to 3 m; a hand or a face alone 0.1 m, a crowd 20 m. Outside these the
// coordinates are in other units than the file says: CMU 85_02 in metres under "mm" spans 1.8 mm.
constexpr double kSmallestSpanMm = 50.0;
constexpr double kLargestSpanMm = 50000.0;

}  // namespace

MarkerSpan measureMarkerSpan(const C3dTake& take, std::size_t frames,
                             const std::function<C3dSamples(std::size_t frame)>& frameAt) {
    const std::vector<std::size_t> markers = take.markerIndices();
    std::vector<double> spans;  // per frame showing 3 markers: its bounding box's longest side
    const std::size_t judged = std::min(frames, kSpanFrames);
    for (std::size_t i = 0; i < judged; ++i) {
        const C3dSamples frame = frameAt(i * frames / judged);
        Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
        int seen = 0;
        for (std::size_t k : markers)
            if (const auto p = frame.position(0, k)) {
                lo = lo.cwiseMin(*p);
                hi = hi.cwiseMax(*p);
                ++seen;
            }
        if (seen >= 3) spans.push_back((hi - lo).maxCoeff());
    }
    if (spans.empty()) return {};
    std::nth_element(spans.begin(), spans.begin() + spans.size() / 2, spans.end());
    return judgeMarkerSpan(take, spans[spans.size() / 2]);
}

MarkerSpan judgeMarkerSpan(const C3dTake& take, double stored) {
    MarkerSpan result;
    result.stored = stored;
    result.mm = stored * take.unitToMm;
    if (!(stored > 0.0) || (result.mm >= kSmallestSpanMm && result.mm <= kLargestSpanMm))
        return result;
    // The units that make the span a body's: nearest 1 m on a log scale.
    struct Unit {
        const char *symbol, *name;
        double mm;
    };
    static const Unit units[] = {{"mm", "millimetres", 1.0},
                                 {"cm", "centimetres", 10.0},
                                 {"m", "metres", 1000.0},
                                 {"in", "inches", 25.4}};
    const Unit* likely = &units[0];
    for (const Unit& u : units)
        if (std::fabs(std::log(stored * u.mm / 1000.0)) <
            std::fabs(std::log(stored * likely->mm / 1000.0)))
            likely = &u;
    result.likelyUnits = likely->symbol;
    const bool stated = take.parameters.find("POINT", "UNITS") != nullptr;
    const std::string said = !take.unitsFrom.empty() ? take.unitsFrom + " says " + take.units
                             : stated                ? "POINT:UNITS says " + take.units
                                      : std::string("millimetres were assumed (no POINT:UNITS)");
    result.doubt = "its markers span " + lengthText(result.mm) + " although " + said +
                   ": are they in " + likely->name + " (" + lengthText(stored * likely->mm) +
                   ")? A body spans 0.3 to 3 m";
    return result;
}

}  // namespace boneless::c3d_detail
