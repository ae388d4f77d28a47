#include "boneless/Alignment.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

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

int visibleRows(const Positions& P) {
    int seen = 0;
    for (Eigen::Index k = 0; k < P.rows(); ++k) seen += P.row(k).allFinite() ? 1 : 0;
    return seen;
}

Similarity levelled(const Similarity& free, const Positions& take, const Positions& mesh,
                    const Vec3& takeUp, const std::optional<Vec3>& meshUp) {
    const Vec3 up = free.R * takeUp;
    int axis = 0;
    up.cwiseAbs().maxCoeff(&axis);
    const Vec3 a = meshUp ? *meshUp : (up[axis] < 0 ? -1.0 : 1.0) * Vec3::Unit(axis);
    const Mat3 level = Eigen::Quaterniond::FromTwoVectors(up, a).toRotationMatrix() * free.R;
    std::vector<Vec3> x, y;
    for (Eigen::Index k = 0; k < take.rows(); ++k)
        if (take.row(k).allFinite() && mesh.row(k).allFinite()) {
            x.push_back(free.scale * (level * take.row(k).transpose()));
            y.push_back(mesh.row(k).transpose());
        }
    Similarity s = free;
    s.R = level;
    if (x.empty()) return s;
    Vec3 xMean = Vec3::Zero(), yMean = Vec3::Zero();
    for (std::size_t k = 0; k < x.size(); ++k) xMean += x[k] / x.size(), yMean += y[k] / y.size();
    // The turn about `a` that brings the centred take nearest the mesh, in closed form.
    double along = 0, across = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
        const Vec3 xc = x[k] - xMean, yc = y[k] - yMean;
        along += (xc - xc.dot(a) * a).dot(yc);
        across += a.cross(xc).dot(yc);
    }
    const Mat3 turn = Eigen::AngleAxisd(std::atan2(across, along), a).toRotationMatrix();
    s.R = turn * level;
    s.t = yMean - turn * xMean;
    return s;
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
        visible[f] = visibleRows(frameAt(f));
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

bool alignsMuchWorse(double chosenMm, double automaticMm) {
    return chosenMm > kMuchWorseAlignmentRatio * automaticMm &&
           chosenMm - automaticMm > kMuchWorseAlignmentMm;
}

}  // namespace boneless
