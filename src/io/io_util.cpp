// Shared I/O helpers: reading a whole file.
#include "io/io_util.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "io/io_error.h"

namespace weir {

std::string readFileBytes(const std::string& path) {
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw IoError("cannot open '" + path + "': " + std::strerror(errno));
    }
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (in.bad()) {
        throw IoError("cannot read '" + path + "': " + std::strerror(errno));
    }
    return std::move(bytes).str();
}

}  // namespace weir
