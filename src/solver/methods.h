// The pressure solvers weir offers, by name: for scene checks, --help and `weir info`. The
// registry itself is solver/method_registry.h.
#pragma once

#include <string>
#include <vector>

namespace weir {

// Name and one-line description of each registered pressure solver, the default first.
struct MethodInfo {
    std::string name, description;
};
std::vector<MethodInfo> pressureSolvers();
// Throws std::invalid_argument naming the allowed solvers if `name` is not one (empty is the
// default); returns the name made concrete.
std::string checkPressureSolver(const std::string& name);

}  // namespace weir
