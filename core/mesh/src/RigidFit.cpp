#include "boneless/RigidFit.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "boneless/Error.h"

namespace boneless {
namespace {

// The rows where both sides are finite, as 3 by n column blocks for Eigen's umeyama().
struct Pairs {
    Eigen::Matrix3Xd from, to;
};

Pairs finitePairs(const Positions& from, const Positions& to) {
    std::vector<int> rows;
    for (int r = 0; r < static_cast<int>(from.rows()); ++r)
        if (from.row(r).allFinite() && to.row(r).allFinite()) rows.push_back(r);
    Pairs p{Eigen::Matrix3Xd(3, rows.size()), Eigen::Matrix3Xd(3, rows.size())};
    for (size_t i = 0; i < rows.size(); ++i) {
        p.from.col(i) = from.row(rows[i]).transpose();
        p.to.col(i) = to.row(rows[i]).transpose();
    }
    return p;
}

}  // namespace

RigidMotion fitRigidMotion(const Positions& from, const Positions& to) {
    const Pairs p = finitePairs(from, to);
    RigidMotion motion;
    if (p.from.cols() == 0) return motion;
    if (p.from.cols() < 3) {  // no rotation to find: the mean translation
        motion.t = (p.to - p.from).rowwise().mean();
        return motion;
    }
    const Eigen::Matrix4d T = Eigen::umeyama(p.from, p.to, false);
    motion.R = T.topLeftCorner<3, 3>();
    motion.t = T.topRightCorner<3, 1>();
    return motion;
}

Similarity fitSimilarity(const Positions& from, const Positions& to) {
    const Pairs p = finitePairs(from, to);
    if (p.from.cols() < 3)
        throw Error("alignment needs at least 3 markers visible at once, got " +
                    std::to_string(p.from.cols()));
    // Collinear markers leave the rotation about their line undetermined.
    const Eigen::Matrix3Xd centred = p.from.colwise() - p.from.rowwise().mean();
    const Eigen::Vector3d sv = Eigen::JacobiSVD<Eigen::Matrix3Xd>(centred).singularValues();
    if (!(sv[1] > 1e-9 * sv[0]))
        throw Error("alignment markers are collinear (or coincide): the rotation is undetermined");
    const Eigen::Matrix4d T = Eigen::umeyama(p.from, p.to, true);
    Similarity s;
    const Mat3 sR = T.topLeftCorner<3, 3>();
    s.scale = std::cbrt(sR.determinant());
    s.R = sR / s.scale;
    s.t = T.topRightCorner<3, 1>();
    return s;
}

double alignmentResidual(const Similarity& s, const Positions& from, const Positions& to) {
    const Pairs p = finitePairs(from, to);
    if (p.from.cols() == 0) return std::numeric_limits<double>::infinity();
    double sum = 0;
    for (Eigen::Index i = 0; i < p.from.cols(); ++i)
        sum += (s.apply(p.from.col(i)) - p.to.col(i)).squaredNorm();
    return std::sqrt(sum / p.from.cols());
}

}  // namespace boneless
