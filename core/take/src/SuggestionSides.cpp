#include "SuggestionSides.h"

#include <cctype>

namespace boneless {

char SideCheck::side(const std::string& label) {
    if (label.size() < 3 || (label[0] != 'L' && label[0] != 'R') ||
        !std::isupper(static_cast<unsigned char>(label[1])))
        return 0;
    return label[0];
}

std::string SideCheck::partner(const std::string& label) {
    std::string other = label;
    if (side(label)) other[0] = label[0] == 'L' ? 'R' : 'L';
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

}  // namespace boneless
