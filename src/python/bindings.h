// What the parts of the Python module share: each file binds one concept into the module.
#pragma once

#include <nanobind/nanobind.h>

#include "scene/scene.h"

namespace weir {

// A scene from what a Python caller passes: a Scene, a file path or built-in name (str), a
// pathlib.Path, or a dict of scene fields; throws SceneError as the CLI does, TypeError otherwise.
Scene sceneFrom(nanobind::handle value);

void bindScene(nanobind::module_& m);       // scene_bindings.cpp
void bindSimulation(nanobind::module_& m);  // simulation_bindings.cpp

}  // namespace weir
