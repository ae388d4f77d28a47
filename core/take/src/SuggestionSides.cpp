#include "SuggestionSides.h"

#include <algorithm>
#include <vector>

#include "boneless/Text.h"

namespace boneless {

namespace {
// Where the marker's own name starts: after a "subject:" prefix, if any.
std::size_t nameStart(const std::string& label) {
    const std::size_t colon = label.find(':');
    return colon == std::string::npos ? 0 : colon + 1;
}
}  // namespace

char SideCheck::side(const std::string& label) {
    const std::size_t i = nameStart(label);
    if (label.size() < i + 3 || (label[i] != 'L' && label[i] != 'R') || !isAsciiUpper(label[i + 1]))
        return 0;
    return label[i];
}

std::string SideCheck::partner(const std::string& label) {
    std::string other = label;
    if (const char s = side(label)) other[nameStart(label)] = s == 'L' ? 'R' : 'L';
    return other;
}

SideCheck::SideCheck(const TriMesh& rest, const Correspondence& picks) {
    Vec3 across = Vec3::Zero(), middle = Vec3::Zero();
    int pairs = 0;
    for (const auto& m : picks.markers) {
        if (side(m.label) != 'L') continue;
        const MarkerMapping* r = picks.find(partner(m.label));
        if (!r) continue;
        const Vec3 a = rest.V.row(m.vertex).transpose(), b = rest.V.row(r->vertex).transpose();
        across += a - b;
        middle += 0.5 * (a + b);
        ++pairs;
    }
    if (pairs == 0 || across.norm() == 0) return;
    known_ = true;
    left_ = across.normalized();
    mid_ = left_.dot(middle / pairs);
    // A twentieth of the mesh's size: markers near the spine may sit a little off the middle.
    margin_ = 0.05 * (rest.V.colwise().maxCoeff() - rest.V.colwise().minCoeff()).norm();
}

std::string SideCheck::mismatch(const std::string& label, const Vec3& restPoint) const {
    const char s = side(label);
    if (!known_ || !s) return {};
    const double lateral = left_.dot(restPoint) - mid_;
    if (s == 'L' && lateral < -margin_) return "named left, but on the mesh's right";
    if (s == 'R' && lateral > margin_) return "named right, but on the mesh's left";
    return {};
}

// Vertices sampled to fit and test the plane, every (n / kMirrorSamples)-th: enough to see a limb
// that is not mirrored.
constexpr int kMirrorSamples = 400;
// The mesh is symmetric when this share of the samples reflects to within kMirrorEdges mean edge
// lengths of a vertex (MakeHuman and the demo reflect onto their own vertices exactly).
constexpr double kMirrorShare = 0.9;
constexpr double kMirrorEdges = 0.5;

MirrorPlane::MirrorPlane(const TriMesh& rest, const SideCheck& sides) {
    if (!sides.known_ || rest.F.rows() == 0) return;
    normal_ = sides.left_;
    offset_ = sides.mid_;
    double edge = 0;
    for (int f = 0; f < rest.F.rows(); ++f)
        edge += (rest.V.row(rest.F(f, 0)) - rest.V.row(rest.F(f, 1))).norm();
    edge /= static_cast<double>(rest.F.rows());
    const int n = rest.vertexCount();
    const int step = std::max(1, n / kMirrorSamples);
    // A few rounds of: match each sample's reflection to its nearest vertex, fit the plane that
    // maps the pairs onto each other (the picks' vertices are a user's clicks, not exact mirrors).
    for (int round = 0; round < 4; ++round) {
        Vec3 across = Vec3::Zero(), middle = Vec3::Zero();
        double weight = 0;
        for (int v = 0; v < n; v += step) {
            const Vec3 a = rest.V.row(v).transpose();
            Eigen::Index b = 0;
            (rest.V.rowwise() - reflect(a).transpose()).rowwise().norm().minCoeff(&b);
            const Vec3 w = a - rest.V.row(b).transpose();
            across += normal_.dot(w) >= 0 ? w : Vec3(-w);
            middle += w.norm() * 0.5 * (a + rest.V.row(b).transpose());
            weight += w.norm();
        }
        if (across.norm() == 0 || weight == 0) return;
        normal_ = across.normalized();
        offset_ = normal_.dot(middle / weight);
    }
    // The plane as fitted: how many samples it reflects onto the mesh.
    int samples = 0, onMesh = 0;
    for (int v = 0; v < n; v += step, ++samples)
        onMesh += (rest.V.rowwise() - reflect(rest.V.row(v).transpose()).transpose())
                      .rowwise()
                      .norm()
                      .minCoeff() <= kMirrorEdges * edge;
    known_ = onMesh >= kMirrorShare * samples;
}

}  // namespace boneless
