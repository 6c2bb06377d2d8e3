// weir.Scene and the functions that find scenes: from a file, a built-in name, JSON text or a dict.
#include <nanobind/nanobind.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "python/bindings.h"

namespace nb = nanobind;

namespace weir {

namespace {

// JSON text of a dict (or any JSON-able value) by Python's own json module.
std::string jsonText(nb::handle value) {
    return nb::cast<std::string>(nb::module_::import_("json").attr("dumps")(value));
}

nb::object jsonValue(const std::string& text) {
    return nb::module_::import_("json").attr("loads")(text);
}

const char* modelName(FluidModelName model) {
    return model == FluidModelName::DeltaSph ? "delta-sph" : "paper";
}

}  // namespace

Scene sceneFrom(nb::handle value) {
    if (nb::isinstance<Scene>(value)) {
        return nb::cast<Scene>(value);
    }
    if (nb::isinstance<nb::str>(value)) {
        return resolveScene(nb::cast<std::string>(value));
    }
    if (nb::isinstance<nb::dict>(value)) {
        return parseScene(jsonText(value), "<dict>");
    }
    // os.PathLike (pathlib.Path): a file.
    if (nb::hasattr(value, "__fspath__")) {
        return loadScene(nb::cast<std::string>(value.attr("__fspath__")()));
    }
    throw nb::type_error(
        "a scene is a weir.Scene, a file path or built-in scene name (str or os.PathLike), or a "
        "dict of scene fields");
}

void bindScene(nb::module_& m) {
    nb::class_<Scene>(m, "Scene",
                      "A scene: container, fluid, obstacles, resolution and timing, read and "
                      "checked as weir run reads a scene file. Immutable: the with_* methods "
                      "return a new scene.")
        .def_static("from_file", &loadScene, nb::arg("path"),
                    "Reads a scene file (JSON). Raises SceneError naming the file, the field, "
                    "the bad value and what is allowed.")
        .def_static("from_json", &parseScene, nb::arg("text"), nb::arg("source") = "<json>",
                    "Reads a scene from JSON text; `source` names it in error messages, and "
                    "mesh obstacle paths are relative to its folder.")
        .def_static(
            "from_dict",
            [](nb::dict fields, const std::string& source) {
                return parseScene(jsonText(fields), source);
            },
            nb::arg("fields"), nb::arg("source") = "<dict>",
            "Reads a scene from a dict of scene fields (as in a scene file).")
        .def_static("builtin", &builtinScene, nb::arg("name"),
                    "A built-in scene by name (weir.builtin_scenes() lists them).")
        .def(
            "with_overrides",
            [](const Scene& scene, nb::handle patch) {
                return withOverrides(scene, nb::isinstance<nb::str>(patch)
                                                ? nb::cast<std::string>(patch)
                                                : jsonText(patch));
            },
            nb::arg("overrides"),
            nb::sig("def with_overrides(self, overrides: dict[str, typing.Any] | str) -> Scene"),
            "The scene with `overrides` (a dict of scene fields, or its JSON text) merged in, "
            "field by field (a JSON merge patch: nested dicts merge, other values replace, None "
            "removes a field), then checked again: e.g. {'fluid': {'viscosity': 0.01}}.")
        .def("with_model", &withFluidModel, nb::arg("model"),
             "The scene with fluid.model set ('delta-sph' or 'paper'); the defaults that follow "
             "the model follow it.")
        .def("with_solver", &withSolver, nb::arg("solver"),
             "The scene with its pressure solver set ('wcsph' or 'dfsph').")
        .def(
            "to_dict", [](const Scene& scene) { return jsonValue(scene.json); },
            nb::sig("def to_dict(self) -> dict[str, typing.Any]"),
            "The scene's fields as read (a dict, as in a scene file).")
        .def_prop_ro(
            "json", [](const Scene& scene) { return scene.json; },
            "The scene as read, compact JSON text.")
        .def_prop_ro(
            "name", [](const Scene& scene) { return scene.name; }, "The scene's name.")
        .def_prop_ro(
            "source", [](const Scene& scene) { return scene.sourcePath; },
            "Where it came from: a file path, '<built-in NAME>', '<json>' or '<dict>'.")
        .def_prop_ro(
            "description", [](const Scene& scene) { return scene.description; },
            "The scene's description, free text.")
        .def_prop_ro(
            "model", [](const Scene& scene) { return std::string(modelName(scene.model)); },
            "The fluid model: 'delta-sph' or 'paper'.")
        .def_prop_ro(
            "solver",
            [](const Scene& scene) { return scene.solver.empty() ? "wcsph" : scene.solver; },
            "The pressure solver: 'wcsph' or 'dfsph'.")
        .def_prop_ro(
            "duration", [](const Scene& scene) { return scene.duration; },
            "Simulated seconds a run covers (time.duration).")
        .def_prop_ro(
            "frame_rate", [](const Scene& scene) { return scene.frameRate; },
            "Frames per simulated second (time.frameRate).")
        .def("__repr__", [](const Scene& scene) {
            return "weir.Scene('" + scene.name + "', source='" + scene.sourcePath + "')";
        });

    m.def("load_scene", &sceneFrom, nb::arg("scene"),
          nb::sig("def load_scene(scene: Scene | str | os.PathLike[str] | dict[str, typing.Any]) "
                  "-> Scene"),
          "A scene from a file path or built-in scene name (as weir run SCENE takes it), a "
          "pathlib.Path, a dict of scene fields, or a Scene (returned as is). Raises SceneError "
          "naming the file, the field and the value, with a did-you-mean for a near name.");
    m.def("builtin_scenes", &builtinSceneNames, "The names of the built-in scenes.");
}

}  // namespace weir
