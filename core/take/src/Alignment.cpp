#include "boneless/Alignment.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "boneless/C3dTake.h"
#include "boneless/Error.h"

namespace boneless {

Positions takeFrame(const C3dTake& take, const std::vector<std::size_t>& points, int frame) {
    Positions P(points.size(), 3);
    for (size_t k = 0; k < points.size(); ++k) {
        const auto p = take.samples.position(frame, points[k]);
        if (p)
            P.row(k) = p->transpose();
        else
            P.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    return P;
}

Calibration calibrate(const C3dTake& take, const std::vector<std::size_t>& points,
                      const Positions& restPositions) {
    return calibrate(
        static_cast<int>(take.frameCount()), [&](int f) { return takeFrame(take, points, f); },
        take.file, restPositions);
}

Calibration calibrate(int frames, const std::function<Positions(int)>& frameAt,
                      const std::string& file, const Positions& restPositions) {
    // Frames showing the most mapped markers are the candidates: all of them when such frames
    // exist, as in the specification; otherwise the best a gappy take has to offer.
    std::vector<int> visible(frames, 0);
    int mostVisible = 0;
    for (int f = 0; f < frames; ++f) {
        const Positions P = frameAt(f);
        for (int k = 0; k < P.rows(); ++k) visible[f] += P.row(k).allFinite() ? 1 : 0;
        mostVisible = std::max(mostVisible, visible[f]);
    }
    Calibration best;
    best.residual = std::numeric_limits<double>::infinity();
    for (int f = 0; f < frames && mostVisible >= 3; ++f) {
        if (visible[f] != mostVisible) continue;
        const Positions P = frameAt(f);
        Similarity s;
        try {
            s = fitSimilarity(P, restPositions);
        } catch (const Error&) {
            continue;
        }
        const double r = alignmentResidual(s, P, restPositions);
        if (r < best.residual) best = {f, s, r, mostVisible};
    }
    if (best.frame < 0)
        throw Error(file +
                    ": no frame shows three or more of the mapped markers in general "
                    "position, so the take cannot be aligned automatically");
    return best;
}

}  // namespace boneless
