// Test support for end-to-end tests of the weir binary: a fixture that runs `weir ARGS` in a fresh
// temporary directory and captures its output, and small text helpers.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace weir::cli_testing {

namespace fs = std::filesystem;

// A 6 x 6 x 4 block of particles at 2 cm in a 30 x 20 x 8 cm box (144 particles): small enough
// to simulate, draw and mesh in a test.
inline constexpr const char* kTinyDrawScene = R"({
    "name": "tiny",
    "container": {"min": [0, 0, 0], "max": [0.3, 0.2, 0.08]},
    "blocks": [{"min": [0, 0, 0], "max": [0.12, 0.12, 0.08]}],
    "particles": {"spacing": 0.02},
    "time": {"duration": 1, "frameRate": 30}
})";

// Whether a program is on PATH (tests that need xvfb-run or ffmpeg skip without it).
inline bool onPath(const std::string& program) {
    return std::system(("command -v " + program + " > /dev/null 2>&1").c_str()) == 0;
}

// Like gmock's HasSubstr, which would need libgmock (the test binary links only gtest).
inline ::testing::AssertionResult contains(const std::string& text, const std::string& part) {
    if (text.find(part) != std::string::npos) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "output lacks \"" << part << "\":\n" << text;
}

inline std::string fileText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The path in single quotes for /bin/sh.
inline std::string quoted(const std::string& text) {
    std::string out = "'";
    for (char c : text) {
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    return out + "'";
}

struct RunResult {
    int exitCode = -1;   // WEXITSTATUS, or -1 when the process did not exit normally
    std::string output;  // stdout and stderr together
};

// Each test works in a fresh directory under the system temp dir, removed at the end; weir runs
// with it as working directory, so a default out/ would land there too.
class Cli : public ::testing::Test {
   protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("weir_cli_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    void writeFile(const std::string& name, const std::string& text) const {
        std::ofstream(dir_ / name, std::ios::binary) << text;
    }

    // Runs `weir ARGS` in the test directory and captures its output.
    RunResult weir(const std::string& args) { return shell(quoted(WEIR_BINARY) + " " + args); }

    // Runs a shell command line in the test directory and captures its output.
    RunResult shell(const std::string& commandLine) {
        const std::string log = path("weir_output_" + std::to_string(runs_++) + ".txt");
        // Passive OpenMP waits: with ctest -j on few cores, spinning threads of parallel test
        // processes would starve each other (a tiny run then takes seconds instead of ms).
        const std::string command = "cd " + quoted(dir_.string()) +
                                    " && export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} && " +
                                    commandLine + " > " + quoted(log) + " 2>&1";
        const int status = std::system(command.c_str());
        RunResult result;
        result.exitCode = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
        result.output = fileText(log);
        fs::remove(log);
        return result;
    }

    // The names in a directory, sorted.
    static std::vector<std::string> entries(const fs::path& dir) {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir)) {
            names.push_back(entry.path().filename().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

    fs::path dir_;
    int runs_ = 0;
};

}  // namespace weir::cli_testing
