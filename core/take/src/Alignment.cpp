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
    return CalibrationSearch(frames, frameAt, file).find(restPositions);
}

CalibrationSearch::CalibrationSearch(int frames, std::function<Positions(int)> frameAt,
                                     std::string file)
    : frames_(std::max(0, frames)), frameAt_(std::move(frameAt)), file_(std::move(file)) {}

namespace {
// `x` as a float no greater than it: a bound kept in 4 bytes stays a bound.
float floatBelow(double x) {
    float f = static_cast<float>(x);
    if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return f;
}
}  // namespace

Calibration CalibrationSearch::find(const Positions& restPositions) {
    constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
    // Frames showing the most mapped markers are the candidates: all of them when such frames
    // exist, as in the specification; otherwise the best a gappy take has to offer. Among them
    // the smallest residual, the earliest frame of equal ones.
    Calibration best;
    best.residual = std::numeric_limits<double>::infinity();
    const auto fit = [&](int f, const Positions& P, int visible) {
        ++framesRead_;
        bound_[f] = kNone;
        Similarity s;
        try {
            s = fitSimilarity(P, restPositions);
        } catch (const Error&) {
            return;  // collinear: no candidate for any rest
        }
        const double r = alignmentResidual(s, P, restPositions);
        if (std::isnan(r)) return;
        bound_[f] = floatBelow(r);
        if (r < best.residual || (r == best.residual && f < best.frame)) {
            best.frame = f;
            best.takeToMesh = s;
            best.residual = r;
            best.visibleMarkers = visible;
        }
    };
    if (!previous_) {
        // One read: a frame is fitted when it shows as many markers as any before it; those
        // before the first frame that shows the most are no candidates after all.
        bound_.assign(frames_, kNone);
        int firstOfMost = 0;
        for (int f = 0; f < frames_; ++f) {
            const Positions P = frameAt_(f);
            const int visible = visibleRows(P);
            if (visible < std::max(3, mostVisible_)) {
                ++framesRead_;
                mostVisible_ = std::max(mostVisible_, visible);
                continue;
            }
            if (visible > mostVisible_) {
                mostVisible_ = visible;
                firstOfMost = f;
                best = Calibration();
                best.residual = std::numeric_limits<double>::infinity();
            }
            fit(f, P, visible);
        }
        std::fill(bound_.begin(), bound_.begin() + firstOfMost, kNone);
    } else {
        // A frame's best fit to this rest is no better than its best fit to the last one less the
        // largest distance between the two rests' rows (the triangle inequality, for the fit to
        // the last rest moved onto this one); `margin` covers the rounding.
        // Rests of other sizes bound nothing: every candidate is fitted again.
        double apart = previous_->rows() == restPositions.rows()
                           ? 0.0
                           : std::numeric_limits<double>::infinity();
        for (Eigen::Index k = 0; k < restPositions.rows() && std::isfinite(apart); ++k) {
            const double d = (restPositions.row(k) - previous_->row(k)).norm();
            apart = std::isfinite(d) ? std::max(apart, d) : std::numeric_limits<double>::infinity();
        }
        const double margin = 1e-9 * (1.0 + restPositions.cwiseAbs().maxCoeff());
        const auto tryFrame = [&](int f) {
            if (std::isnan(bound_[f])) return;
            const double bound = double(bound_[f]) - apart - margin;
            if (bound > best.residual)
                bound_[f] = floatBelow(bound);  // a bound at this rest, for the next find
            else
                fit(f, frameAt_(f), mostVisible_);
        };
        // The last find's frame first: its residual is near the best, so the bound rules out
        // most frames before they are read.
        if (best_ >= 0) tryFrame(best_);
        for (int f = 0; f < frames_; ++f)
            if (f != best_) tryFrame(f);
    }
    previous_ = restPositions;
    if (best.frame < 0)
        throw Error(file_ +
                    ": no frame shows three or more of the mapped markers in general "
                    "position, so the take cannot be aligned automatically");
    best_ = best.frame;
    return best;
}

bool alignsMuchWorse(double chosenMm, double automaticMm) {
    return chosenMm > kMuchWorseAlignmentRatio * automaticMm &&
           chosenMm - automaticMm > kMuchWorseAlignmentMm;
}

}  // namespace boneless
