// Out-of-line error helpers of core/check.h.
#include "core/check.h"

namespace weir {

void throwCudaError(const char* expr, const char* file, int line, const char* what) {
    std::ostringstream msg;
    msg << "CUDA error: " << what << " in " << expr << " at " << file << ":" << line;
    throw CudaError(msg.str());
}

}  // namespace weir
