// PvdCollection: a ParaView .pvd time series of frame files, rewritten atomically on each frame.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "io/io_error.h"

namespace weir {

class PvdCollection {
   public:
    // The collection file is <dir>/<baseName>.pvd; nothing is written until the first add().
    PvdCollection(std::string dir, std::string baseName);

    // Records (time, file) and rewrites the .pvd atomically with every entry so far. `file` is
    // relative to dir; adding a file already listed replaces its time. Throws IoError.
    void add(double time, const std::string& file);

    const std::string& path() const { return path_; }
    std::size_t size() const { return entries_.size(); }

   private:
    void rewrite() const;

    std::string path_;
    std::vector<std::pair<double, std::string>> entries_;  // (time, relative file)
};

}  // namespace weir
