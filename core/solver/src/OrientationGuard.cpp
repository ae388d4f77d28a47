#include "OrientationGuard.h"

#include <cmath>

#include "boneless/Metrics.h"

namespace boneless {

namespace {
Vec3 faceNormal(const TriMesh& mesh, const Positions& V, int f) {
    const Vec3 a = V.row(mesh.F(f, 0)), b = V.row(mesh.F(f, 1)), c = V.row(mesh.F(f, 2));
    return (b - a).cross(c - a);
}
}  // namespace

OrientationGuard::OrientationGuard(const TriMesh& rest, double weight, double threshold)
    : rest_(&rest), threshold_(threshold) {
    const int faces = rest.faceCount();
    restArea2_.resize(faces);
    double total = 0;
    const double diagonal = boundingBoxDiagonal(rest.V, rest.F);
    // A face with no area has no orientation to guard: an area of 0 leaves it out.
    for (int f = 0; f < faces; ++f)
        total += restArea2_[f] = zeroArea(rest.V.row(rest.F(f, 0)), rest.V.row(rest.F(f, 1)),
                                          rest.V.row(rest.F(f, 2)), diagonal)
                                     ? 0.0
                                     : faceNormal(rest, rest.V, f).norm();
    const double meanArea = faces ? 0.5 * total / faces : 0.0;
    scale_ = std::sqrt(weight * meanArea);
}

std::vector<Vec3> OrientationGuard::reference(const Positions& V) const {
    std::vector<Vec3> u = carriedRestNormals(rest_->F, V, rest_->V);
    for (size_t f = 0; f < u.size(); ++f) {
        const double length = u[f].norm();
        u[f] = restArea2_[f] > 0 && length > 0 ? Vec3(u[f] / length) : Vec3::Zero();
    }
    return u;
}

double OrientationGuard::gap(const Positions& V, int f, const Vec3& u) const {
    return threshold_ - faceNormal(*rest_, V, f).dot(u) / restArea2_[f];
}

double OrientationGuard::energy(const Positions& V) const {
    const std::vector<Vec3> u = reference(V);
    double e = 0;
    for (int f = 0; f < rest_->faceCount(); ++f) {
        if (u[f].isZero()) continue;
        const double g = gap(V, f, u[f]);
        if (g > 0) e += g * g;
    }
    return 0.5 * scale_ * scale_ * e;
}

double OrientationGuard::linearise(const Positions& V, std::vector<Term>& active) const {
    const std::vector<Vec3> u = reference(V);
    active.clear();
    double e = 0;
    for (int f = 0; f < rest_->faceCount(); ++f) {
        if (u[f].isZero()) continue;
        const double g = gap(V, f, u[f]);
        if (g <= 0) continue;
        // n = (b − a) × (c − a), so ∂(n·u)/∂a = (b − c) × u and cyclically.
        Term t{f, scale_ * g, {}};
        for (int c = 0; c < 3; ++c) {
            const Vec3 next = V.row(rest_->F(f, (c + 1) % 3));
            const Vec3 prev = V.row(rest_->F(f, (c + 2) % 3));
            t.derivative[c] = -scale_ * (next - prev).cross(u[f]) / restArea2_[f];
        }
        e += 0.5 * t.residual * t.residual;
        active.push_back(t);
    }
    return e;
}

void OrientationGuard::addGradient(const std::vector<Term>& active, Eigen::VectorXd& g) const {
    for (const auto& t : active)
        for (int c = 0; c < 3; ++c)
            g.segment<3>(3 * rest_->F(t.face, c)) += t.residual * t.derivative[c];
}

void OrientationGuard::addProduct(const std::vector<Term>& active, const Eigen::VectorXd& x,
                                  Eigen::VectorXd& y) const {
    for (const auto& t : active) {
        double dx = 0;
        for (int c = 0; c < 3; ++c)
            dx += t.derivative[c].dot(x.segment<3>(3 * rest_->F(t.face, c)));
        for (int c = 0; c < 3; ++c) y.segment<3>(3 * rest_->F(t.face, c)) += dx * t.derivative[c];
    }
}

bool OrientationGuard::anyTurnedOver(const std::vector<Term>& active) const {
    for (const auto& t : active)
        if (t.residual > scale_ * threshold_) return true;
    return false;
}

}  // namespace boneless
