// The output folder of `weir run`: what an earlier run left in it, refusing to mix two runs'
// frames, clearing it for --overwrite, and removing the temporaries of a killed run.
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>

namespace weir {

struct EarlierRun {
    std::size_t frames = 0;  // frame files (frame_NNNNN in any frame format)
    std::string scene;       // its scene's name from frames.json; empty: not recorded
};

// The frames an earlier run left in dir (frame files or a frames.json), or nothing.
std::optional<EarlierRun> findEarlierRun(const std::string& dir);

// Removes what a run writes into dir and nothing else: its frame files, frame.pvd, frames.json,
// the frames.usda of --usd, and the images/frame_NNNNN.png and mesh/surface_NNNNN.<mesh format>
// of --render and --mesh.
// Returns how many files it removed.
std::size_t removeEarlierRun(const std::string& dir);

// Before a run writes into dir: removes the temporaries that killed runs left there; refuses
// (std::invalid_argument naming the folder, the earlier run and the way out) a folder that holds
// an earlier run's frames unless `overwrite`, which removes them first. Says what it did on log.
void prepareRunFolder(const std::string& dir, bool overwrite, std::ostream& log);

}  // namespace weir
