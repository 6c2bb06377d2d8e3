// --frame N and --frames A:B over a run's frame index.
#include "cli/frame_selection.h"

#include <regex>
#include <stdexcept>

namespace weir {

std::vector<FrameEntry> selectFrames(const std::vector<FrameEntry>& all,
                                     const std::optional<std::int64_t>& frame,
                                     const std::string& range, const std::string& dir) {
    if (!frame && range.empty()) {
        return all;
    }
    const std::string holds = all.empty()
                                  ? "no frames"
                                  : "frames " + std::to_string(all.front().index) + " to " +
                                        std::to_string(all.back().index) + " (" +
                                        std::to_string(all.size()) + " listed in its frames.json)";
    if (frame && !range.empty()) {
        throw std::invalid_argument(
            "--frame and --frames both given: pick one frame (--frame N) "
            "or a range (--frames A:B)");
    }
    std::int64_t first = 0, last = INT64_MAX;
    std::string asked;
    if (frame) {
        first = last = *frame;
        asked = "--frame " + std::to_string(*frame);
    } else {
        asked = "--frames " + range;
        std::smatch match;
        if (!std::regex_match(range, match, std::regex(R"((\d*):(\d*))")) ||
            (match[1].length() == 0 && match[2].length() == 0) || match[1].length() > 9 ||
            match[2].length() > 9) {
            throw std::invalid_argument(asked +
                                        ": write A:B (frames A to B, both included), A: or :B");
        }
        if (match[1].length() > 0) {
            first = std::stoll(match[1]);
        }
        if (match[2].length() > 0) {
            last = std::stoll(match[2]);
        }
        if (first > last) {
            throw std::invalid_argument(asked + ": the first frame is after the last");
        }
    }
    std::vector<FrameEntry> selected;
    for (const FrameEntry& entry : all) {
        if (entry.index >= first && entry.index <= last) {
            selected.push_back(entry);
        }
    }
    if (selected.empty()) {
        throw std::invalid_argument(asked + " selects no frame: " + dir + " holds " + holds);
    }
    return selected;
}

}  // namespace weir
