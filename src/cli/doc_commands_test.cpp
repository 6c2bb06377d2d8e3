// Every command in README.md and docs/ runs as written (issue 20). The shell commands of each
// ```sh block are extracted and run in order, one folder per document, from a copy of the
// repository root's layout (build/weir, examples/, scenes/, tools/; `weir` on PATH). What the
// test changes, so that the suite stays fast on two cores: it shrinks sizes, as each command's own
// options allow (`weir run`: 1000 particles, images of 160 x 90; `weir view`: 1000 particles, 3
// frames; `weir bench`: 1k particles, 2 steps; `weir render`: 160 x 90 pixels, 1 sample; Blender
// with tools/blender/weir_blender.py: 160 x 90 pixels, 4 samples). Frame counts stay as written,
// as later commands pick frames by number. A command marked with a comment "needs ffmpeg", "needs
// a GPU" (or "2 GPUs"), "needs mpirun", "needs a display" (Xvfb's), "needs blender" or "needs a
// cluster" is skipped where that is missing; the set-up scripts (`bash scripts/...`) install
// packages and build, and are run by people and CI, not by this suite.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_test_support.h"
#include "io/optional_formats.h"
#include "scene/scene.h"

namespace weir {
namespace {

namespace fs = std::filesystem;
using namespace cli_testing;

struct DocCommand {
    std::string file;     // relative to the source tree
    int line = 0;         // of the command's first line
    std::string command;  // continuation lines joined, comment removed
    std::string comment;  // the comment after it, "" if none
};

std::string trim(const std::string& text) {
    const std::size_t first = text.find_first_not_of(" \t");
    const std::size_t last = text.find_last_not_of(" \t");
    return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

// The commands of a Markdown file's ```sh blocks.
std::vector<DocCommand> commandsOf(const fs::path& root, const std::string& file) {
    std::ifstream in(root / file);
    std::vector<DocCommand> commands;
    bool inShell = false, inOther = false;
    std::string pending;
    int pendingLine = 0, lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        const std::string stripped = trim(line);
        if (stripped.rfind("```", 0) == 0) {
            if (inShell || inOther) {
                inShell = inOther = false;
            } else {
                const std::string language = trim(stripped.substr(3));
                inShell = language == "sh" || language == "bash";
                inOther = !inShell;
            }
            continue;
        }
        if (!inShell || stripped.empty() || stripped[0] == '#') {
            continue;
        }
        if (pending.empty()) {
            pendingLine = lineNumber;
        }
        if (stripped.back() == '\\') {
            pending += stripped.substr(0, stripped.size() - 1) + " ";
            continue;
        }
        pending += stripped;
        DocCommand command{file, pendingLine, pending, ""};
        const std::size_t hash = pending.find(" #");
        if (hash != std::string::npos) {
            command.command = trim(pending.substr(0, hash));
            command.comment = trim(pending.substr(hash + 2));
        }
        commands.push_back(command);
        pending.clear();
    }
    return commands;
}

std::vector<std::string> words(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> list;
    for (std::string word; in >> word;) {
        list.push_back(word);
    }
    return list;
}

std::string joined(const std::vector<std::string>& list) {
    std::string text;
    for (const std::string& w : list) {
        text += (text.empty() ? "" : " ") + w;
    }
    return text;
}

// The weir subcommand the command runs ("run", "render", ...), or "" for other programs.
std::string subcommandOf(const std::vector<std::string>& w, std::size_t* at) {
    for (std::size_t i = 0; i + 1 < w.size(); ++i) {
        if (w[i] == "weir" || w[i] == "build/weir" || w[i] == "./build/weir") {
            *at = i + 1;
            return w[i + 1];
        }
    }
    return "";
}

// Drops `option VALUE` for each of the options and appends the replacements.
std::vector<std::string> replaced(std::vector<std::string> w,
                                  const std::vector<std::string>& options,
                                  const std::vector<std::string>& replacement) {
    for (std::size_t i = 0; i < w.size();) {
        if (std::find(options.begin(), options.end(), w[i]) != options.end() && i + 1 < w.size()) {
            w.erase(w.begin() + std::ptrdiff_t(i), w.begin() + std::ptrdiff_t(i) + 2);
        } else {
            ++i;
        }
    }
    w.insert(w.end(), replacement.begin(), replacement.end());
    return w;
}

// The command with its sizes shrunk (see the file comment).
std::string shrunk(const std::string& command) {
    std::vector<std::string> w = words(command);
    std::size_t at = 0;
    const std::string sub = subcommandOf(w, &at);
    if (sub == "run") {
        w = replaced(w, {"--particles", "-n", "--width", "--height"},
                     {"--particles", "1000", "--width", "160", "--height", "90"});
    } else if (sub == "view") {
        w = replaced(w, {"--particles", "-n", "--max-frames"},
                     {"--particles", "1000", "--max-frames", "3"});
    } else if (sub == "bench") {
        w = replaced(w, {"--sizes", "--steps", "--warmup", "--settle"},
                     {"--sizes", "1k", "--steps", "2", "--warmup", "1", "--settle", "0.01"});
    } else if (sub == "render") {
        w = replaced(w, {"--width", "--height", "--samples"},
                     {"--width", "160", "--height", "90", "--samples", "1"});
    } else if (command.find("weir_blender.py") != std::string::npos) {
        w = replaced(w, {"--width", "--height", "--samples"},
                     {"--width", "160", "--height", "90", "--samples", "4"});
    }
    return joined(w);
}

// What the command needs beyond a CPU, by its marker comment; checks that the docs mark what
// the command evidently needs.
struct Needs {
    bool ffmpeg = false, gpu = false, mpirun = false, display = false, blender = false,
         cluster = false;
    int gpus = 0;
};

Needs needsOf(const DocCommand& c) {
    Needs n;
    n.ffmpeg = std::regex_search(c.comment, std::regex(R"(needs.*\bffmpeg\b)"));
    n.gpu = std::regex_search(c.comment, std::regex(R"(needs.*\bGPUs?\b)"));
    n.mpirun = std::regex_search(c.comment, std::regex(R"(needs.*\bmpirun\b)"));
    n.display = std::regex_search(c.comment, std::regex(R"(needs.*\bdisplay\b)"));
    n.blender = std::regex_search(c.comment, std::regex(R"(needs.*\bblender\b)"));
    n.cluster = std::regex_search(c.comment, std::regex(R"(needs.*\b(cluster|hostfile)\b)"));
    const std::smatch count = [&] {
        std::smatch m;
        std::regex_search(c.comment, m, std::regex(R"(needs.*\b(\d+) GPUs\b)"));
        return m;
    }();
    n.gpus = count.empty() ? (n.gpu ? 1 : 0) : std::stoi(count[1]);
    return n;
}

class DocCommands : public Cli {
   protected:
    // A folder laid out like the repository root for the commands, and `weir` on PATH.
    void layOut() {
        const fs::path source(WEIR_SOURCE_DIR);
        fs::create_directories(dir_ / "build");
        fs::create_directories(dir_ / "bin");
        fs::create_symlink(WEIR_BINARY, dir_ / "build" / "weir");
        fs::create_symlink(WEIR_BINARY, dir_ / "bin" / "weir");
        for (const char* folder : {"examples", "scenes", "tools"}) {
            fs::create_directory_symlink(source / folder, dir_ / folder);
        }
    }

    // The GPUs this machine has for weir: none unless weir picks CUDA, then nvidia-smi's count.
    int gpuCount() {
        if (!contains(weir("info").output, "auto backend picks: cuda")) {
            return 0;
        }
        const RunResult list = shell("nvidia-smi -L 2>/dev/null | grep -c '^GPU'");
        return list.exitCode == 0 ? std::max(1, std::atoi(list.output.c_str())) : 1;
    }

    void runDocument(const std::string& file) {
        const std::vector<DocCommand> commands = commandsOf(WEIR_SOURCE_DIR, file);
        ASSERT_FALSE(commands.empty()) << file << " has no ```sh commands";
        layOut();
        const int gpus = gpuCount();
        int ran = 0, skipped = 0;
        for (const DocCommand& c : commands) {
            const std::string where = c.file + ":" + std::to_string(c.line) + ": " + c.command;
            SCOPED_TRACE(where);
            const Needs needs = needsOf(c);
            // The docs say what a command needs.
            if (c.command.find("--video") != std::string::npos ||
                c.command.find("--record") != std::string::npos) {
                EXPECT_TRUE(needs.ffmpeg) << "mark it: # needs ffmpeg";
            }
            if (c.command.find("mpirun") != std::string::npos) {
                EXPECT_TRUE(needs.mpirun) << "mark it: # needs mpirun";
            }
            if (std::regex_search(c.command, std::regex(R"(--backends? cuda|cuda-)"))) {
                EXPECT_TRUE(needs.gpu) << "mark it: # needs a GPU";
            }
            if (std::regex_search(c.command, std::regex(R"(\bweir view\b)"))) {
                EXPECT_TRUE(needs.display) << "mark it: # needs a display";
            }
            if (std::regex_search(c.command, std::regex(R"(^blender\b)"))) {
                EXPECT_TRUE(needs.blender) << "mark it: # needs blender";
            }
            std::string why;
            if (c.command.rfind("bash scripts/", 0) == 0) {
                why = "a set-up script (installs packages and builds)";
            } else if (needs.cluster) {
                why = "needs a cluster";
            } else if (needs.gpus > gpus) {
                why = "needs " + std::to_string(needs.gpus) + " GPU(s), this machine has " +
                      std::to_string(gpus);
            } else if (needs.ffmpeg && !onPath("ffmpeg")) {
                why = "no ffmpeg";
            } else if (needs.mpirun && !onPath("mpirun")) {
                why = "no mpirun";
            } else if (needs.display && !onPath("xvfb-run")) {
                why = "no display (xvfb-run)";
            } else if (needs.blender && !onPath("blender")) {
                why = "no blender";
            } else if (!openVdbBuilt() &&
                       std::regex_search(c.command,
                                         std::regex(R"(--(mesh-)?format [a-z,]*\bvdb\b)"))) {
                why = "built without OpenVDB";
            }
            if (!why.empty()) {
                std::cout << "[ skipped  ] " << where << " (" << why << ")\n";
                ++skipped;
                continue;
            }
            std::string line = shrunk(c.command);
#if !defined(WEIR_HAS_RENDER)
            // A weir without rendering: `weir render` and `weir view` cannot run; `weir run
            // --render` still writes the frames later commands read, without images.
            if (std::regex_search(line, std::regex(R"(\bweir (render|view)\b)"))) {
                std::cout << "[ skipped  ] " << where << " (built without rendering)\n";
                ++skipped;
                continue;
            }
            // (Whole options only: --surface-field stays.)
            line = std::regex_replace(line, std::regex(R"( --render(?![-\w])| --surface(?![-\w]))"),
                                      "");
#endif
            if (needs.display) {
                line = "xvfb-run -a -s '-screen 0 640x480x24' " + line;
            }
            // As root, OpenMPI wants to be told (docs/cluster.md says so too).
            const RunResult result = shell("export PATH=" + quoted((dir_ / "bin").string()) +
                                           ":$PATH OMPI_ALLOW_RUN_AS_ROOT=1 "
                                           "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 && " +
                                           line);
            EXPECT_EQ(result.exitCode, 0) << "as run: " << line << "\n" << result.output;
            ++ran;
        }
        std::cout << "[ doc      ] " << file << ": " << ran << " commands ran, " << skipped
                  << " skipped\n";
        EXPECT_GT(ran, 0);
    }
};

TEST_F(DocCommands, ReadmeRunsAsWritten) { runDocument("README.md"); }
TEST_F(DocCommands, RenderingRunsAsWritten) { runDocument("docs/rendering.md"); }
TEST_F(DocCommands, ClusterRunsAsWritten) { runDocument("docs/cluster.md"); }
TEST_F(DocCommands, ScenesRunAsWritten) { runDocument("docs/scenes.md"); }
TEST_F(DocCommands, PipelineRunsAsWritten) { runDocument("docs/pipeline.md"); }
TEST_F(DocCommands, SurfacesRunAsWritten) { runDocument("docs/surfaces.md"); }
TEST_F(DocCommands, BenchRunsAsWritten) { runDocument("bench/README.md"); }

// The scene file the README shows is the shipped example, and that example loads (its rock mesh
// is shipped beside it).
TEST(DocScene, TheReadmesSceneIsExamplesShowcaseAndLoads) {
    const fs::path source(WEIR_SOURCE_DIR);
    const std::string readme = fileText(source / "README.md");
    const std::size_t start = readme.find("```json\n");
    ASSERT_NE(start, std::string::npos);
    const std::size_t end = readme.find("```", start + 8);
    const std::string shown = readme.substr(start + 8, end - start - 8);
    const std::string shipped = fileText(source / "examples" / "showcase.json");
    EXPECT_EQ(shown, shipped) << "README.md's scene and examples/showcase.json differ";
    const Scene scene = loadScene((source / "examples" / "showcase.json").string());
    ASSERT_EQ(scene.obstacleMeshes.size(), 1u);
    EXPECT_GT(scene.obstacleMeshes[0].triangles.size(), 10u);
}

}  // namespace
}  // namespace weir
