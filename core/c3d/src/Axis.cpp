#include "boneless/Axis.h"

namespace boneless {

std::string axisName(const Eigen::Vector3d& axis) {
    int k = 0;
    axis.cwiseAbs().maxCoeff(&k);
    return std::string(axis[k] < 0 ? "-" : "+") + "xyz"[k];
}

std::optional<Eigen::Vector3d> parseAxis(const std::string& name) {
    if (name.size() != 2 || (name[0] != '+' && name[0] != '-') || name[1] < 'x' || name[1] > 'z')
        return std::nullopt;
    return (name[0] == '-' ? -1.0 : 1.0) * Eigen::Vector3d::Unit(name[1] - 'x');
}

}  // namespace boneless
