// frames.json parsing and frame reading by extension.
#include "io/frame_index.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/frame_formats.h"
#include "io/frame_reader.h"

namespace weir {

namespace fs = std::filesystem;

namespace {

nlohmann::json loadIndex(const std::string& dir, const std::string& indexPath) {
    if (!fs::is_directory(dir)) {
        throw IoError("frames directory '" + dir +
                      "' does not exist (give the output directory of "
                      "`weir run`, e.g. out/dam_break)");
    }
    std::ifstream in(indexPath);
    if (!in) {
        throw IoError("cannot read '" + indexPath + "': no such file (is '" + dir +
                      "' the output directory of `weir run`?)");
    }
    nlohmann::json index;
    try {
        in >> index;
    } catch (const nlohmann::json::exception& e) {
        throw IoError("cannot read '" + indexPath + "': not JSON (" + e.what() + ")");
    }
    return index;
}

}  // namespace

nlohmann::json makeRunRecord(const std::string& sceneName, const std::string& sceneSource,
                             const std::string& sceneJson, std::int64_t particles, double spacing,
                             const std::string& version) {
    std::string source = sceneSource;
    if (source.rfind("<", 0) != 0) {
        std::error_code ec;
        const fs::path absolute = fs::absolute(source, ec);
        source = ec ? source : absolute.lexically_normal().string();
    }
    nlohmann::json definition = nlohmann::json::object();
    if (!sceneJson.empty()) {
        definition = nlohmann::json::parse(sceneJson);
    }
    return {{"scene", {{"name", sceneName}, {"source", source}, {"definition", definition}}},
            {"particles", particles},
            {"spacing", spacing},
            {"weir", version}};
}

RunRecord readRunRecord(const std::string& dir) {
    const std::string indexPath = (fs::path(dir) / "frames.json").string();
    const nlohmann::json index = loadIndex(dir, indexPath);
    RunRecord record;
    if (!index.is_object()) {
        return record;
    }
    const auto text = [&](const nlohmann::json& object, const char* key) {
        return object.contains(key) && object[key].is_string() ? object[key].get<std::string>()
                                                               : std::string();
    };
    if (index.contains("scene") && index["scene"].is_object()) {
        const nlohmann::json& scene = index["scene"];
        record.sceneName = text(scene, "name");
        record.sceneSource = text(scene, "source");
        if (scene.contains("definition") && scene["definition"].is_object()) {
            record.sceneJson = scene["definition"].dump();
        }
    }
    if (index.contains("spacing") && index["spacing"].is_number()) {
        record.spacing = index["spacing"].get<double>();
    }
    if (index.contains("particles") && index["particles"].is_number_integer()) {
        record.particles = index["particles"].get<std::int64_t>();
    }
    record.format = text(index, "format");
    if (index.contains("frames") && index["frames"].is_array()) {
        record.frames = index["frames"].size();
    }
    return record;
}

namespace {

// A frame's "bodies": [{"position": [3], "orientation": [4], "velocity": [3],
// "angularVelocity": [3]}, ...] (io/frame_writer.h); bad(field, what) makes the error.
template <class Bad>
std::vector<BodyPose> readBodyPoses(const nlohmann::json& list, const std::string& at, Bad& bad) {
    if (!list.is_array()) {
        throw bad(at, "is not an array of body poses");
    }
    std::vector<BodyPose> poses;
    for (std::size_t k = 0; k < list.size(); ++k) {
        const std::string where = at + "[" + std::to_string(k) + "]";
        auto numbers = [&](const char* key, std::size_t count, double* out) {
            const nlohmann::json* value =
                list[k].is_object() && list[k].contains(key) ? &list[k][key] : nullptr;
            bool ok = value != nullptr && value->is_array() && value->size() == count;
            for (std::size_t i = 0; ok && i < count; ++i) {
                ok = (*value)[i].is_number() && std::isfinite((*value)[i].get<double>());
                if (ok) {
                    out[i] = (*value)[i].get<double>();
                }
            }
            if (!ok) {
                throw bad(where + "." + key,
                          "is missing or not " + std::to_string(count) + " finite numbers");
            }
        };
        BodyPose pose;
        double v[3];
        numbers("position", 3, v);
        pose.position = Vec3d(v[0], v[1], v[2]);
        numbers("orientation", 4, pose.orientation);
        numbers("velocity", 3, v);
        pose.velocity = Vec3d(v[0], v[1], v[2]);
        numbers("angularVelocity", 3, v);
        pose.angularVelocity = Vec3d(v[0], v[1], v[2]);
        poses.push_back(pose);
    }
    return poses;
}

}  // namespace

std::vector<FrameEntry> readFrameIndex(const std::string& dir) {
    const std::string indexPath = (fs::path(dir) / "frames.json").string();
    const nlohmann::json index = loadIndex(dir, indexPath);
    auto bad = [&](const std::string& field, const std::string& what) {
        return IoError("frames index '" + indexPath + "': field '" + field + "' " + what);
    };
    if (!index.is_object() || !index.contains("frames") || !index["frames"].is_array()) {
        throw bad("frames", "is missing or not an array");
    }
    std::vector<FrameEntry> frames;
    for (std::size_t i = 0; i < index["frames"].size(); ++i) {
        const nlohmann::json& entry = index["frames"][i];
        const std::string at = "frames[" + std::to_string(i) + "]";
        if (!entry.is_object() || !entry.contains("index") || !entry["index"].is_number_integer() ||
            entry["index"].get<long long>() < 0 || entry["index"].get<long long>() > 99999999) {
            throw bad(at + ".index", "is missing or not an integer in 0..99999999");
        }
        if (!entry.contains("time") || !entry["time"].is_number()) {
            throw bad(at + ".time", "is missing or not a number");
        }
        if (!entry.contains("file") || !entry["file"].is_string() ||
            entry["file"].get<std::string>().empty()) {
            throw bad(at + ".file", "is missing or not a file name");
        }
        frames.push_back({entry["index"].get<int>(),
                          entry["time"].get<double>(),
                          (fs::path(dir) / entry["file"].get<std::string>()).string(),
                          {}});
        if (entry.contains("bodies")) {
            frames.back().bodies = readBodyPoses(entry["bodies"], at + ".bodies", bad);
        }
    }
    if (frames.empty()) {
        throw bad("frames", "lists no frames");
    }
    std::sort(frames.begin(), frames.end(),
              [](const FrameEntry& a, const FrameEntry& b) { return a.index < b.index; });
    return frames;
}

HostParticles readFrameFile(const std::string& path) {
    HostParticles particles = frameFormatOfFile(path).entry().read(path, nullptr);
    checkFramePositions(particles, path);
    return particles;
}

}  // namespace weir
