// FrameWriter and the frame format names.
#include "io/frame_writer.h"

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/csv_writer.h"
#include "io/ply_writer.h"
#include "io/vtu_writer.h"

namespace weir {

namespace fs = std::filesystem;

FrameFormat parseFrameFormat(const std::string& text) {
    for (FrameFormat format : {FrameFormat::Vtu, FrameFormat::Ply, FrameFormat::Csv}) {
        if (text == formatExtension(format)) {
            return format;
        }
    }
    throw std::invalid_argument("unknown frame format \"" + text + "\" (allowed: vtu, ply, csv)");
}

std::string formatExtension(FrameFormat format) {
    switch (format) {
        case FrameFormat::Vtu:
            return "vtu";
        case FrameFormat::Ply:
            return "ply";
        case FrameFormat::Csv:
            return "csv";
    }
    throw std::invalid_argument("invalid FrameFormat value " + std::to_string(int(format)));
}

FrameWriter::FrameWriter(std::string dir, FrameFormat format, std::string baseName)
    : dir_(std::move(dir)), format_(format), baseName_(std::move(baseName)) {
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec || !fs::is_directory(dir_)) {
        throw IoError("cannot create frame directory '" + dir_ +
                      "': " + (ec ? ec.message() : "a file of that name exists"));
    }
    if (format_ == FrameFormat::Vtu) {
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
    switch (format_) {
        case FrameFormat::Vtu:
            writeVtu(path, particles, time);
            break;
        case FrameFormat::Ply:
            writePly(path, particles);
            break;
        case FrameFormat::Csv:
            writeCsv(path, particles);
            break;
    }
    const std::string file = frameFileName(frameIndex);
    frames_[frameIndex] = {time, file};
    if (pvd_) {
        pvd_->add(time, file);
    }
    writeIndex();
}

void FrameWriter::writeIndex() const {
    nlohmann::json frames = nlohmann::json::array();
    for (const auto& [index, entry] : frames_) {
        frames.push_back({{"index", index}, {"time", entry.first}, {"file", entry.second}});
    }
    const nlohmann::json index = {
        {"format", formatExtension(format_)}, {"count", frames_.size()}, {"frames", frames}};
    writeFileAtomically(indexPath(), [&](std::ostream& out) { out << index.dump(2) << '\n'; });
}

}  // namespace weir
