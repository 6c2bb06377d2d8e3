// A run's whitewater on disk: whitewater_NNNNN.ply per fluid frame and whitewater.json, the
// index that lists them with their counts and the settings they were made with, in a folder of
// their own (by default FRAMES/whitewater/).
#pragma once

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "whitewater/whitewater.h"

namespace weir {

constexpr const char* kWhitewaterFolder = "whitewater";      // inside a run's frames folder
constexpr const char* kWhitewaterIndex = "whitewater.json";  // inside the whitewater folder

// "whitewater_00012.ply".
std::string whitewaterFileName(std::int64_t index);

// The whitewater file of fluid frame `index` in `dir`, or "" when there is none.
std::string findWhitewaterFile(const std::string& dir, std::int64_t index);

// What one frame came to.
struct WhitewaterFrameReport {
    std::size_t spray = 0, foam = 0, bubbles = 0;
    WhitewaterStep step;
    double seconds = 0;  // to advance (not to write)
    std::size_t total() const { return spray + foam + bubbles; }
};

// Takes a run's fluid frames in time order and writes the whitewater of each: the first frame's
// is empty (nothing has been generated yet), each later one advanced from the frame before.
// Files are written atomically, the index after each frame, so that an interrupted run leaves
// an index of what it wrote.
class WhitewaterSequence {
   public:
    WhitewaterSequence(const std::string& outDir, const WhitewaterScale& scale,
                       const WhitewaterSettings& settings);

    WhitewaterFrameReport add(std::int64_t index, double time, const HostParticles& fluid);

    const std::string& outDir() const { return outDir_; }
    const Whitewater& whitewater() const { return whitewater_; }
    int frames() const { return frames_; }
    // "N frames in DIR/ (spray/foam/bubbles at the last, ms per frame)".
    std::string summary() const;

   private:
    std::string outDir_;
    Whitewater whitewater_;
    HostParticles previous_;
    std::int64_t previousIndex_ = 0;
    double previousTime_ = 0;
    int frames_ = 0;
    double seconds_ = 0;
    WhitewaterFrameReport last_;
    nlohmann::json index_;
};

}  // namespace weir
