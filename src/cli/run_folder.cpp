// Run folders: earlier runs found by their file names and frames.json, removed file by file.
#include "cli/run_folder.h"

#include <filesystem>
#include <regex>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/frame_formats.h"
#include "io/frame_index.h"
#include "io/mesh_writer.h"
#include "whitewater/whitewater_files.h"

namespace weir {

namespace {

namespace fs = std::filesystem;

// frame_NNNNN.<any frame format>: the names FrameWriter gives.
bool isFrameFile(const std::string& name) {
    static const std::regex frame([] {
        std::string formats;
        for (const std::string& format : frameFormatNames()) {
            formats += (formats.empty() ? "" : "|") + format;
        }
        return "frame_\\d{5,}\\.(" + formats + ")";
    }());
    return std::regex_match(name, frame);
}

// The files in dir whose names match, sorted out of a directory listing.
std::size_t removeMatching(const fs::path& dir, const std::regex& pattern) {
    std::size_t removed = 0;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
        return 0;
    }
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (entry.is_regular_file(ec) && std::regex_match(name, pattern)) {
            removed += fs::remove(entry.path(), ec) ? 1 : 0;
        }
    }
    return removed;
}

}  // namespace

std::optional<EarlierRun> findEarlierRun(const std::string& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
        return std::nullopt;
    }
    EarlierRun run;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        run.frames += isFrameFile(entry.path().filename().string()) ? 1 : 0;
    }
    const bool indexed = fs::exists(fs::path(dir) / "frames.json", ec);
    if (run.frames == 0 && !indexed) {
        return std::nullopt;
    }
    if (indexed) {
        try {
            run.scene = readRunRecord(dir).sceneName;
        } catch (const std::exception&) {
            // an index that does not parse still marks the folder as a run's
        }
    }
    return run;
}

std::size_t removeEarlierRun(const std::string& dir) {
    const fs::path root(dir);
    std::size_t removed = 0;
    std::error_code ec;
    if (fs::is_directory(root, ec)) {
        for (const auto& entry : fs::directory_iterator(root, ec)) {
            const std::string name = entry.path().filename().string();
            if (entry.is_regular_file(ec) && (isFrameFile(name) || name == "frame.pvd" ||
                                              name == "frames.json" || name == "frames.usda")) {
                removed += fs::remove(entry.path(), ec) ? 1 : 0;
            }
        }
    }
    removed += removeMatching(root / "images", std::regex(R"(frame_\d{5,}\.png)"));
    std::string meshFiles = R"(surface_\d{5,}\.()";  // surface_NNNNN.(obj|ply|...)
    for (const MeshFormatEntry& entry : meshFormatTable()) {
        meshFiles.append(meshFiles.back() == '(' ? "" : "|").append(entry.name);
    }
    removed += removeMatching(root / "mesh", std::regex(meshFiles.append(")")));
    removed += removeMatching(root / kWhitewaterFolder,
                              std::regex(R"(whitewater_\d{5,}\.ply|whitewater\.json)"));
    return removed;
}

void prepareRunFolder(const std::string& dir, bool overwrite, std::ostream& log) {
    std::size_t stale = 0;
    for (const fs::path& folder : {fs::path(dir), fs::path(dir) / "images", fs::path(dir) / "mesh",
                                   fs::path(dir) / kWhitewaterFolder}) {
        stale += removeStaleTemporaries(folder.string()).size();
    }
    if (stale > 0) {
        log << "weir: removed " << stale << " temporary file" << (stale == 1 ? "" : "s")
            << " that a killed run left in " << dir << "/\n";
    }
    const std::optional<EarlierRun> earlier = findEarlierRun(dir);
    if (!earlier) {
        return;
    }
    const std::string what = std::to_string(earlier->frames) + " frame" +
                             (earlier->frames == 1 ? "" : "s") + " of an earlier run" +
                             (earlier->scene.empty() ? "" : " of scene '" + earlier->scene + "'");
    if (!overwrite) {
        throw std::invalid_argument(
            "the output folder " + dir + "/ holds the " + what +
            " (see its frames.json); pass --overwrite to replace them, or --out DIR to write the "
            "new frames elsewhere");
    }
    const std::size_t removed = removeEarlierRun(dir);
    log << "weir: --overwrite: removed the " << what << " from " << dir << "/ (" << removed
        << " files)\n";
}

}  // namespace weir
