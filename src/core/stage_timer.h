// Per-stage wall times of the step (grid, density, force, integrate), as medians over steps.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace weir {

// Samples in milliseconds for each named stage, one sample per step.
class StageTimes {
   public:
    void add(const std::string& stage, double ms) { samples_[stage].push_back(ms); }
    void clear() { samples_.clear(); }
    const std::map<std::string, std::vector<double>>& samples() const { return samples_; }
    // Median of a stage's samples, 0 if it has none.
    double median(const std::string& stage) const;
    // Sum of per-stage medians (the paper's "total time").
    double totalMedian() const;

   private:
    std::map<std::string, std::vector<double>> samples_;
};

}  // namespace weir
