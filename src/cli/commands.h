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
    std::string neighbours = "auto";
    std::optional<std::int64_t> particles;
    std::optional<std::int64_t> frames;
    std::string outDir;  // empty: out/<scene name>
    std::string format = "vtu";
    bool explain = false;
    bool quiet = false;
};

struct BenchOptions {
    std::string scene;                   // file or built-in name; empty: dam break
    std::string sizes = "10k,50k";       // particle counts, k/M suffixes allowed
    std::string columns = "auto";        // cpu-brute,cpu-grid,...,cuda-dense or auto
    int steps = 20;                      // timed steps (median per stage)
    int warmup = 3;                      // untimed steps before timing
    double settle = 0.1;                 // simulated seconds before timing: a fluid in motion
    double budget = 60;                  // seconds per (size, column); longer runs are skipped
    std::string outDir = "bench-out";
    bool noPlot = false;
};

int runCommand(const RunOptions& options);
int benchCommand(const BenchOptions& options);
int infoCommand();

}  // namespace weir
