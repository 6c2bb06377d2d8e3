// weir bench's "point sprite rendering" row, as in the paper's Tables 1-3: the particles drawn as
// sphere-shaded point sprites, offscreen through EGL on the GPU (or Mesa without one).
#pragma once

#include <memory>

#include "cli/commands.h"

namespace weir {

// Throws RenderError when no OpenGL 3.3 context can be made.
std::unique_ptr<SpriteDrawTimer> makeSpriteDrawTimer();

}  // namespace weir
