// writeFileAtomically: temporary file, stream checks, rename.
#include "io/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>

namespace weir {

namespace {

// The OS reason for the last failure, or a fallback when the library left errno unset.
std::string osReason(const char* fallback) { return errno != 0 ? std::strerror(errno) : fallback; }

// NAME.tmp.PID.N: pid + counter, unique across processes and across threads of this one, and the
// pattern removeStaleTemporaries knows.
std::string temporaryPath(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

}  // namespace

void writeFileAtomicallyByName(const std::string& path,
                               const std::function<void(const std::string&)>& writeTemporary) {
    const std::string tmpPath = temporaryPath(path);
    const auto removeTmp = [&] {
        std::error_code ignored;
        std::filesystem::remove(tmpPath, ignored);
    };
    try {
        writeTemporary(tmpPath);
    } catch (...) {
        removeTmp();
        throw;
    }
    std::error_code ec;
    if (!std::filesystem::is_regular_file(tmpPath, ec)) {
        throw IoError("cannot write '" + path + "': the temporary '" + tmpPath +
                      "' was not written");
    }
    std::filesystem::rename(tmpPath, path, ec);
    if (ec) {
        removeTmp();
        throw IoError("cannot write '" + path + "': cannot rename temporary '" + tmpPath +
                      "' over it: " + ec.message());
    }
}

void writeFileAtomically(const std::string& path,
                         const std::function<void(std::ostream&)>& writeBody) {
    writeFileAtomicallyByName(path, [&](const std::string& tmpPath) {
        const auto fail = [&](const std::string& what, const std::string& reason) {
            throw IoError("cannot write '" + path + "': " + what + ": " + reason);
        };
        errno = 0;
        std::ofstream out(tmpPath, std::ios::binary | std::ios::trunc);
        if (!out) {
            fail("cannot create temporary '" + tmpPath + "'", osReason("open failed"));
        }
        errno = 0;
        writeBody(out);
        out.flush();  // a failed write inside writeBody left its errno; keep it for the message
        if (!out) {
            fail("write failed", osReason("stream error"));
        }
        errno = 0;
        out.close();
        if (!out) {
            fail("close failed", osReason("stream error"));
        }
    });
}

std::vector<std::string> removeStaleTemporaries(const std::string& dir) {
    std::vector<std::string> removed;
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) {
        return removed;
    }
    static const std::regex temporary(R"(.+\.tmp\.(\d+)(\..*)?)");
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        std::smatch match;
        if (!entry.is_regular_file(ec) || !std::regex_match(name, match, temporary)) {
            continue;
        }
        if (match[1].length() > 9) {
            continue;  // not a process id
        }
        const long pid = std::stol(match[1]);
        // A process that still runs (or that we may not signal) may still be writing it.
        const bool alive = pid > 0 && (::kill(pid_t(pid), 0) == 0 || errno == EPERM);
        if (!alive && std::filesystem::remove(entry.path(), ec)) {
            removed.push_back(name);
        }
    }
    return removed;
}

}  // namespace weir
