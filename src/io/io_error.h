// IoError: the exception thrown when a frame or index file cannot be written or read.
#pragma once

#include <stdexcept>

namespace weir {

// The message names the file and what went wrong (the OS reason, or what is malformed).
class IoError : public std::runtime_error {
   public:
    using std::runtime_error::runtime_error;
};

}  // namespace weir
