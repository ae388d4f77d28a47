#pragma once

// A take worn by two actors, shared by the CLI's and the app's tests of solves that must not
// replace another actor's.

#include <string>

#include "boneless/C3dTake.h"

namespace taketest {

// `one`'s markers twice, as subjects "walker" and "other" ("walker:LFHD", "other:LFHD"), the
// second actor `apartMm` along the take's x.
inline boneless::C3dTake wornByTwoActors(const boneless::C3dTake& one, double apartMm = 1500.0) {
    boneless::C3dTake two = one;
    const std::size_t n = one.points.size();
    two.points.clear();
    two.samples = boneless::C3dSamples(one.frameCount(), 2 * n);
    for (const std::string subject : {"walker", "other"}) {
        const std::size_t base = two.points.size();
        for (std::size_t p = 0; p < n; ++p) {
            boneless::C3dPoint point = one.points[p];
            point.subject = subject;
            point.label = subject + ":" + point.name;
            two.points.push_back(point);
            for (std::size_t f = 0; f < one.frameCount(); ++f)
                if (const auto x = one.samples.position(f, p))
                    two.samples.set(f, base + p, x->x() + (base ? apartMm : 0.0), x->y(), x->z());
        }
    }
    return two;
}

}  // namespace taketest
