// Medians of per-stage timing samples.
#include "core/stage_timer.h"

#include <algorithm>

namespace weir {

double StageTimes::median(const std::string& stage) const {
    auto it = samples_.find(stage);
    if (it == samples_.end() || it->second.empty()) {
        return 0.0;
    }
    std::vector<double> v = it->second;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

double StageTimes::totalMedian() const {
    double total = 0.0;
    for (const auto& [stage, values] : samples_) {
        total += median(stage);
    }
    return total;
}

}  // namespace weir
