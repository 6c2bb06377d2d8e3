// The registry of pressure solvers. Adding one is a folder under solver/ (its stages, its class
// with kName and kDescription, its tests) and one entry in Methods below.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "solver/dfsph/dfsph.h"
#include "solver/methods.h"
#include "solver/pressure_solver.h"
#include "solver/wcsph/wcsph.h"

namespace weir {

template <template <class> class... Method>
struct MethodTable {};

// The registry: the first entry is the default.
using Methods = MethodTable<Wcsph, Dfsph>;

// The pressure solver named `name` (empty: the default) on backend Exec; nullptr if unknown.
template <class Exec, template <class> class... Method>
std::unique_ptr<PressureSolver<Exec>> makePressureSolverFrom(MethodTable<Method...>,
                                                             const std::string& name,
                                                             const SphParams& params) {
    std::unique_ptr<PressureSolver<Exec>> made;
    bool first = true;
    auto tryOne = [&](auto* tag, const char* methodName) {
        using M = std::remove_pointer_t<decltype(tag)>;
        if (!made && ((name.empty() && first) || name == methodName)) {
            made = std::make_unique<M>(params);
        }
        first = false;
    };
    (tryOne(static_cast<Method<Exec>*>(nullptr), Method<Exec>::kName), ...);
    return made;
}

template <class Exec>
std::unique_ptr<PressureSolver<Exec>> makePressureSolver(const std::string& name,
                                                         const SphParams& params) {
    return makePressureSolverFrom<Exec>(Methods{}, name, params);
}

}  // namespace weir
