// The commands that draw: `weir render` (frames to PNG images and a video), `weir run --render`
// and `weir view` (an interactive window).
#pragma once

#include "cli/commands.h"

namespace weir {

int renderCommand(const RenderOptions& options);
// For `weir run --render`: renders every frame to <out>/images/ (or options.outDir) with the
// options' size, colouring, camera and mode. Throws std::invalid_argument for bad options.
std::unique_ptr<RunObserver> makeRunRenderer(const RenderOptions& options);
int viewCommand(const ViewOptions& options);

}  // namespace weir
