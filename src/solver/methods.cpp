// The registry's names and descriptions, for scene checks, --help and `weir info`.
#include <stdexcept>

#include "core/exec_cpu.h"
#include "solver/method_registry.h"

namespace weir {

namespace {

template <template <class> class... Method>
std::vector<MethodInfo> infosOf(MethodTable<Method...>) {
    return {MethodInfo{Method<CpuExec>::kName, Method<CpuExec>::kDescription}...};
}

}  // namespace

std::vector<MethodInfo> pressureSolvers() { return infosOf(Methods{}); }

std::string checkPressureSolver(const std::string& name) {
    const std::vector<MethodInfo> all = pressureSolvers();
    if (name.empty()) {
        return all.front().name;
    }
    std::string allowed;
    for (const MethodInfo& method : all) {
        if (method.name == name) {
            return name;
        }
        allowed += (allowed.empty() ? "" : ", ") + method.name;
    }
    throw std::invalid_argument("unknown pressure solver '" + name + "': allowed are " + allowed);
}

}  // namespace weir
