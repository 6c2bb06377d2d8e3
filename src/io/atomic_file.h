// writeFileAtomically: write a file through a temporary beside it, then rename over the target.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "io/io_error.h"

namespace weir {

// Writes `path` so that readers (and an interrupted run) only ever see the old file or the
// complete new one: writeBody fills a uniquely named temporary in the same directory, which is
// then renamed over `path`. On failure the temporary is removed; I/O failures throw IoError
// naming the path and the OS reason, an exception thrown by writeBody propagates unchanged.
void writeFileAtomically(const std::string& path,
                         const std::function<void(std::ostream&)>& writeBody);

// The same for writers that write a file by its name (a library such as OpenVDB):
// writeTemporary(tmpPath) creates and fills the temporary, which is then renamed over `path`.
// A writeTemporary that throws, or leaves no file, leaves nothing behind (IoError as above).
void writeFileAtomicallyByName(
    const std::string& path, const std::function<void(const std::string& tmpPath)>& writeTemporary);

// Removes the temporaries that writers killed mid-write left in `dir` (not its subfolders):
// files named NAME.tmp.PID or NAME.tmp.PID.SUFFIX (writeFileAtomically's names, and the video's)
// whose process PID no longer runs. Returns the names removed. A missing dir removes nothing.
std::vector<std::string> removeStaleTemporaries(const std::string& dir);

}  // namespace weir
