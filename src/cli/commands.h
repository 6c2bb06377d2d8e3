// The weir subcommands, each a function from parsed options to an exit code.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace weir {

// Exit codes shared by all commands.
constexpr int kExitOk = 0;
constexpr int kExitError = 1;     // bad scene, I/O failure, not enough memory
constexpr int kExitUsage = 2;     // bad command-line arguments
constexpr int kExitBlowUp = 3;    // the simulation blew up; frames already written stay

struct RunOptions {
    std::string scene;  // file path or built-in name; empty: the built-in dam break
    std::string backend = "auto";
    std::string neighbours = "grid";
    std::optional<std::int64_t> particles;
    std::optional<std::int64_t> frames;
    std::string outDir;  // empty: out/<scene name>
    std::string format = "vtu";
    bool explain = false;
    bool quiet = false;
};

int runCommand(const RunOptions& options);
int infoCommand();

}  // namespace weir
