// Error checks: WEIR_CUDA_CHECK for CUDA calls, WEIR_REQUIRE for internal invariants.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace weir {

// A failure of the CUDA runtime or of a kernel launch.
class CudaError : public std::runtime_error {
   public:
    using std::runtime_error::runtime_error;
};

// A simulation that cannot go on: bad parameters, memory too small, a blown-up state.
class SimulationError : public std::runtime_error {
   public:
    using std::runtime_error::runtime_error;
};

[[noreturn]] void throwCudaError(const char* expr, const char* file, int line, const char* what);

}  // namespace weir

#define WEIR_CUDA_CHECK(expr)                                                                \
    do {                                                                                     \
        cudaError_t weirErr_ = (expr);                                                       \
        if (weirErr_ != cudaSuccess) {                                                       \
            ::weir::throwCudaError(#expr, __FILE__, __LINE__, cudaGetErrorString(weirErr_)); \
        }                                                                                    \
    } while (0)

#define WEIR_REQUIRE(cond, msg)                            \
    do {                                                   \
        if (!(cond)) {                                     \
            std::ostringstream weirMsg_;                   \
            weirMsg_ << msg;                               \
            throw ::weir::SimulationError(weirMsg_.str()); \
        }                                                  \
    } while (0)
