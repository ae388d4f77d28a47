#pragma once

#include <algorithm>
#include <vector>

namespace boneless {

// The median, of an even count the mean of the two middle values (0 when empty): one rule for
// every time per frame the project reports (the sidecar, eval, boneless-bench).
inline double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const auto middle = values.begin() + values.size() / 2;
    std::nth_element(values.begin(), middle, values.end());
    if (values.size() % 2) return *middle;
    return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

}  // namespace boneless
