// The neighbour modes' names and the choice of Auto.
#include "solver/neighbour_search.h"

#include <stdexcept>

namespace weir {

NeighbourMode parseNeighbourMode(const std::string& name) {
    if (name == "grid") {
        return NeighbourMode::Grid;
    }
    if (name == "dense") {
        return NeighbourMode::Dense;
    }
    if (name == "brute") {
        return NeighbourMode::Brute;
    }
    if (name == "auto") {
        return NeighbourMode::Auto;
    }
    throw std::invalid_argument("unknown neighbour search '" + name +
                                "': allowed are auto, grid, dense, brute");
}

const char* neighbourModeName(NeighbourMode mode) {
    switch (mode) {
        case NeighbourMode::Grid:
            return "grid";
        case NeighbourMode::Dense:
            return "dense";
        case NeighbourMode::Brute:
            return "brute";
        default:
            return "auto";
    }
}

NeighbourMode resolveNeighbourMode(NeighbourMode mode, const GridSpec& grid, std::int64_t n) {
    if (mode != NeighbourMode::Auto) {
        return mode;
    }
    return denseGridSuits(grid, n) ? NeighbourMode::Dense : NeighbourMode::Grid;
}

}  // namespace weir
