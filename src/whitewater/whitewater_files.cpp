// WhitewaterSequence: advance, write the frame's file, rewrite the index.
#include "whitewater/whitewater_files.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "io/atomic_file.h"
#include "whitewater/whitewater_ply.h"

namespace weir {

namespace fs = std::filesystem;

std::string whitewaterFileName(std::int64_t index) {
    char name[40];
    std::snprintf(name, sizeof name, "whitewater_%05lld.ply", static_cast<long long>(index));
    return name;
}

std::string findWhitewaterFile(const std::string& dir, std::int64_t index) {
    const fs::path path = fs::path(dir) / whitewaterFileName(index);
    std::error_code error;
    return fs::is_regular_file(path, error) ? path.string() : std::string();
}

WhitewaterSequence::WhitewaterSequence(const std::string& outDir, const WhitewaterScale& scale,
                                       const WhitewaterSettings& settings)
    : outDir_(outDir), whitewater_(scale, settings) {
    std::error_code error;
    fs::create_directories(outDir_, error);
    if (error) {
        throw IoError("cannot create the whitewater folder '" + outDir_ + "': " + error.message());
    }
    const WhitewaterSettings& s = whitewater_.settings();
    index_["method"] = "Ihmsen, Akinci, Becker & Teschner 2012: spray, foam and bubbles";
    index_["columns"] = "x y z vx vy vz kind lifetime (kind 0 spray, 1 foam, 2 bubble)";
    index_["scale"] = {{"spacing", scale.spacing},
                       {"neighbourRadius", scale.neighbourRadius()},
                       {"flowSpeed", scale.flowSpeed}};
    index_["settings"] = {{"trappedAir", {s.trappedAirMin, s.trappedAirMax}},
                          {"waveCrest", {s.waveCrestMin, s.waveCrestMax}},
                          {"kineticSpeed", {s.kineticSpeedMin, s.kineticSpeedMax}},
                          {"trappedAirRate", s.trappedAirRate},
                          {"waveCrestRate", s.waveCrestRate},
                          {"sprayBelow", s.sprayBelow},
                          {"bubbleAbove", s.bubbleAbove},
                          {"foamLifetime", s.foamLifetime},
                          {"maxParticles", s.maxParticles}};
    index_["frames"] = nlohmann::json::array();
}

WhitewaterFrameReport WhitewaterSequence::add(std::int64_t index, double time,
                                              const HostParticles& fluid) {
    WhitewaterFrameReport report;
    const auto start = std::chrono::steady_clock::now();
    if (frames_ > 0) {
        report.step = whitewater_.advance(previous_, previousIndex_, fluid, time - previousTime_);
    }
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const DiffuseParticles& p = whitewater_.particles();
    report.spray = p.count(DiffuseKind::Spray);
    report.foam = p.count(DiffuseKind::Foam);
    report.bubbles = p.count(DiffuseKind::Bubble);
    const std::string name = whitewaterFileName(index);
    writeWhitewaterPly((fs::path(outDir_) / name).string(), p);
    index_["frames"].push_back({{"index", index},
                                {"time", time},
                                {"file", name},
                                {"spray", report.spray},
                                {"foam", report.foam},
                                {"bubbles", report.bubbles}});
    const std::string text = index_.dump(1);
    writeFileAtomically((fs::path(outDir_) / kWhitewaterIndex).string(),
                        [&](std::ostream& out) { out << text << "\n"; });
    previous_ = fluid;
    previousIndex_ = index;
    previousTime_ = time;
    ++frames_;
    seconds_ += report.seconds;
    last_ = report;
    return report;
}

std::string WhitewaterSequence::summary() const {
    std::ostringstream out;
    out << frames_ << " whitewater frame" << (frames_ == 1 ? "" : "s") << " in " << outDir_ << "/ ("
        << last_.spray << " spray, " << last_.foam << " foam, " << last_.bubbles
        << " bubbles at the last; "
        << (frames_ > 1 ? std::lround(1000 * seconds_ / (frames_ - 1)) : 0)
        << " ms per frame to advance)";
    return out.str();
}

}  // namespace weir
