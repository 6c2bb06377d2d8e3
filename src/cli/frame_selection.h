// Which frames of a run `weir render` and `weir mesh` work on: all, one (--frame N) or a range
// (--frames A:B), for a quick look at one moment before a whole sequence.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/frame_index.h"

namespace weir {

// The entries of `all` (a run's frames, sorted by index) that --frame `frame` or --frames `range`
// select: "A:B" is frames A to B, both included; "A:" from A on, ":B" up to B. Neither given: all.
// Throws std::invalid_argument naming the option, the value and the frames `dir` holds when the
// text is malformed, both are given or nothing is selected.
std::vector<FrameEntry> selectFrames(const std::vector<FrameEntry>& all,
                                     const std::optional<std::int64_t>& frame,
                                     const std::string& range, const std::string& dir);

}  // namespace weir
