// FrameWriter: frame files through the format table, the .pvd series and frames.json.
#include "io/frame_writer.h"

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "io/atomic_file.h"

namespace weir {

namespace fs = std::filesystem;

FrameWriter::FrameWriter(std::string dir, FrameFormat format, std::string baseName)
    : dir_(std::move(dir)), format_(format), baseName_(std::move(baseName)) {
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec || !fs::is_directory(dir_)) {
        throw IoError("cannot create frame directory '" + dir_ +
                      "': " + (ec ? ec.message() : "a file of that name exists"));
    }
    if (format_.entry().pvdSeries) {
        pvd_.emplace(dir_, baseName_);
    }
}

std::string FrameWriter::frameFileName(int frameIndex) const {
    char number[16];
    std::snprintf(number, sizeof(number), "_%05d.", frameIndex);
    return baseName_ + number + formatExtension(format_);
}

std::string FrameWriter::framePath(int frameIndex) const {
    return (fs::path(dir_) / frameFileName(frameIndex)).string();
}

std::string FrameWriter::indexPath() const { return (fs::path(dir_) / "frames.json").string(); }

void FrameWriter::write(int frameIndex, double time, const HostParticles& particles) {
    if (frameIndex < 0) {
        throw std::invalid_argument("frame index must be >= 0, got " + std::to_string(frameIndex));
    }
    const std::string path = framePath(frameIndex);
    format_.entry().write(path, particles, {time, spacing_, voxelSize_});
    const std::string file = frameFileName(frameIndex);
    frames_[frameIndex] = {time, file};
    if (!particles.bodies.empty()) {
        nlohmann::json poses = nlohmann::json::array();
        auto triple = [](const Vec3d& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
        for (const BodyPose& b : particles.bodies) {
            poses.push_back(
                {{"position", triple(b.position)},
                 {"orientation",
                  {b.orientation[0], b.orientation[1], b.orientation[2], b.orientation[3]}},
                 {"velocity", triple(b.velocity)},
                 {"angularVelocity", triple(b.angularVelocity)}});
        }
        bodies_[frameIndex] = std::move(poses);
    }
    if (!particles.id.empty()) {  // a count that changes (emitters and sinks)
        counts_[frameIndex] = particles.size();
    }
    if (pvd_) {
        pvd_->add(time, file);
    }
    writeIndex();
}

void FrameWriter::writeIndex() const {
    nlohmann::json frames = nlohmann::json::array();
    for (const auto& [index, entry] : frames_) {
        frames.push_back({{"index", index}, {"time", entry.first}, {"file", entry.second}});
        if (const auto poses = bodies_.find(index); poses != bodies_.end()) {
            frames.back()["bodies"] = poses->second;
        }
        if (const auto count = counts_.find(index); count != counts_.end()) {
            frames.back()["particles"] = count->second;
        }
    }
    nlohmann::json index = record_;
    index["format"] = formatExtension(format_);
    index["count"] = frames_.size();
    index["frames"] = frames;
    writeFileAtomically(indexPath(), [&](std::ostream& out) { out << index.dump(2) << '\n'; });
}

}  // namespace weir
