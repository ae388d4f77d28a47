#include "boneless/Alignment.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "boneless/C3dTake.h"
#include "boneless/Error.h"

namespace boneless {

Similarity fitSimilarity(const Positions& from, const Positions& to) {
    std::vector<int> rows;
    for (int r = 0; r < from.rows(); ++r)
        if (from.row(r).allFinite() && to.row(r).allFinite()) rows.push_back(r);
    if (rows.size() < 3)
        throw Error("alignment needs at least 3 markers visible at once, got " +
                    std::to_string(rows.size()));
    Eigen::Matrix3Xd a(3, rows.size()), b(3, rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
        a.col(i) = from.row(rows[i]).transpose();
        b.col(i) = to.row(rows[i]).transpose();
    }
    // Collinear markers leave the rotation about their line undetermined.
    const Eigen::Matrix3Xd centred = a.colwise() - a.rowwise().mean();
    const Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(centred);
    const Eigen::Vector3d sv = svd.singularValues();
    if (!(sv[1] > 1e-9 * sv[0]))
        throw Error("alignment markers are collinear (or coincide): the rotation is undetermined");
    const Eigen::Matrix4d T = Eigen::umeyama(a, b, true);
    Similarity s;
    const Mat3 sR = T.topLeftCorner<3, 3>();
    s.scale = std::cbrt(sR.determinant());
    s.R = sR / s.scale;
    s.t = T.topRightCorner<3, 1>();
    return s;
}

double alignmentResidual(const Similarity& s, const Positions& from, const Positions& to) {
    double sum = 0;
    int count = 0;
    for (int r = 0; r < from.rows(); ++r)
        if (from.row(r).allFinite() && to.row(r).allFinite()) {
            sum += (s.apply(from.row(r).transpose()) - to.row(r).transpose()).squaredNorm();
            ++count;
        }
    return count ? std::sqrt(sum / count) : std::numeric_limits<double>::infinity();
}

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
    // Frames showing the most mapped markers are the candidates: all of them when such frames
    // exist, as in the specification; otherwise the best a gappy take has to offer.
    const int frames = static_cast<int>(take.frameCount());
    std::vector<int> visible(frames, 0);
    int mostVisible = 0;
    for (int f = 0; f < frames; ++f) {
        for (std::size_t p : points) visible[f] += take.samples.valid(f, p) ? 1 : 0;
        mostVisible = std::max(mostVisible, visible[f]);
    }
    Calibration best;
    best.residual = std::numeric_limits<double>::infinity();
    for (int f = 0; f < frames && mostVisible >= 3; ++f) {
        if (visible[f] != mostVisible) continue;
        const Positions P = takeFrame(take, points, f);
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
        throw Error(take.file +
                    ": no frame shows three or more of the mapped markers in general "
                    "position, so the take cannot be aligned automatically");
    return best;
}

}  // namespace boneless
