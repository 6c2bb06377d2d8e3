// The scene files of scenes/*.json, embedded at build time (see cmake/embed_scenes.cmake).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace weir {

// (file stem, JSON text) for each shipped scene, sorted by file name.
const std::vector<std::pair<std::string, std::string>>& embeddedSceneFiles();

}  // namespace weir
