#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

namespace boneless {

// "+x", "-y", …: a signed coordinate axis as options, sidecars and messages name it.
std::string axisName(const Eigen::Vector3d& axis);
// The signed coordinate axis `name` ("+x" … "-z") stands for, or nothing.
std::optional<Eigen::Vector3d> parseAxis(const std::string& name);

}  // namespace boneless
