// A live progress line on a terminal (frame, simulated time, steps/s, ETA), log lines otherwise.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

namespace weir {

// One status line on stderr: rewritten in place on a terminal, a plain log line otherwise.
class StatusLine {
   public:
    StatusLine();
    bool live() const { return live_; }
    void show(const char* text);
    // Ends a live line so that later output starts on a fresh line.
    void finish();

   private:
    bool live_;
    bool open_ = false;
};

class Progress {
   public:
    Progress(std::int64_t totalFrames, bool quiet);
    // Reports that `frame` of totalFrames is written, at simulated time t after `steps` steps.
    void update(std::int64_t frame, double simTime, long long steps);
    // Ends the live line (if any) so that later output starts on a fresh line.
    void finish();
    // Text shown after the numbers of the following updates (e.g. the density deviation).
    void setNote(std::string note) { note_ = std::move(note); }
    double elapsedSeconds() const;

   private:
    std::int64_t total_;
    bool quiet_;
    StatusLine line_;
    std::string note_;
    std::chrono::steady_clock::time_point start_;
};

// Progress over a list of items (images, meshes): "LABEL i/N  X ms each  elapsed  ETA", live on
// a terminal, about ten log lines otherwise.
class ItemProgress {
   public:
    ItemProgress(std::string label, std::size_t total, bool quiet);
    void update(std::size_t done);
    void finish();
    double elapsedSeconds() const;

   private:
    std::string label_;
    std::size_t total_;
    bool quiet_;
    StatusLine line_;
    std::chrono::steady_clock::time_point start_;
};

std::string formatDuration(double seconds);
// `value` to `digits` significant digits for a log line (no trailing noise): 0.000741, 12.3, 4270.
std::string rounded(double value, int digits);

}  // namespace weir
