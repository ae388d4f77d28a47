#pragma once

// Whether a take's markers span what a body does in the units the file states (docs/c3d.md,
// "A take's units"): CMU 85_02 with its coordinates in metres under POINT:UNITS "mm" spans 1.8 mm.

#include <cstddef>
#include <functional>
#include <string>

#include "boneless/C3dTake.h"

namespace boneless {

class C3dFrameReader;

struct MarkerSpan {
    // The median over frames showing 3 markers of their bounding box's longest side, in mm as
    // the take's units say; 0 when no frame shows 3.
    double mm = 0.0;
    // When that span is no body's (outside 50 mm to 50 m): "its markers span 1.8 mm although
    // POINT:UNITS says mm: are they in metres (1.8 m)? A body spans 0.3 to 3 m", and the units
    // that make it one's ("m"); both "" otherwise.
    std::string doubt, likelyUnits;
};

// Over up to 256 frames spread across the take's `frames` (frameAt(f) gives frame f alone), the
// frames the readers judge the take's vertical by.
MarkerSpan measureMarkerSpan(const C3dTake& take, std::size_t frames,
                             const std::function<C3dSamples(std::size_t frame)>& frameAt);
// Of a take read whole, and of one streamed.
MarkerSpan measureMarkerSpan(const C3dTake& take);
MarkerSpan measureMarkerSpan(const C3dFrameReader& reader);

}  // namespace boneless
