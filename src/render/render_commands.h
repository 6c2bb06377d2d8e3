// The commands that draw: `weir render` (frames to PNG images and a video), `weir run --render`
// and `weir view` (an interactive window).
#pragma once

#include "cli/commands.h"

namespace weir {

int renderCommand(const RenderOptions& options);
// `weir run` that also renders every frame to <out>/images/.
int runRenderCommand(const RunOptions& options);
int viewCommand(const ViewOptions& options);

}  // namespace weir
