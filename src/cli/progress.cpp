// Progress display for long runs.
#include "cli/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <utility>

namespace weir {

std::string formatDuration(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0) {
        return "--:--";
    }
    long s = long(seconds + 0.5);
    char buf[32];
    if (s >= 3600) {
        std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
    } else {
        std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
    }
    return buf;
}

std::string rounded(double value, int digits) {
    char buf[48];
    if (std::isfinite(value) && std::abs(value) >= std::pow(10.0, digits - 1)) {
        std::snprintf(buf, sizeof buf, "%.0f", value);  // whole numbers stay whole, not 4.27e+03
    } else {
        std::snprintf(buf, sizeof buf, "%.*g", digits, value);
    }
    return buf;
}

StatusLine::StatusLine() : live_(isatty(fileno(stderr)) != 0) {}

void StatusLine::show(const char* text) {
    if (live_) {
        std::fprintf(stderr, "\r%s\033[K", text);
        open_ = true;
    } else {
        std::fprintf(stderr, "%s\n", text);
    }
    std::fflush(stderr);
}

void StatusLine::finish() {
    if (open_) {
        std::fprintf(stderr, "\n");
        open_ = false;
    }
}

Progress::Progress(std::int64_t totalFrames, bool quiet)
    : total_(totalFrames), quiet_(quiet), start_(std::chrono::steady_clock::now()) {}

double Progress::elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(std::int64_t frame, double simTime, long long steps) {
    if (quiet_) {
        return;
    }
    double elapsed = elapsedSeconds();
    double stepsPerSecond = elapsed > 0 ? double(steps) / elapsed : 0;
    double eta = frame > 0 ? elapsed * double(total_ - frame) / double(frame) : NAN;
    char line[300];
    std::snprintf(line, sizeof line,
                  "frame %lld/%lld  t = %.3f s  %.0f steps/s  elapsed %s  ETA %s%s%s",
                  (long long)frame, (long long)total_, simTime, stepsPerSecond,
                  formatDuration(elapsed).c_str(), formatDuration(eta).c_str(),
                  note_.empty() ? "" : "  ", note_.c_str());
    line_.show(line);
}

void Progress::finish() { line_.finish(); }

ItemProgress::ItemProgress(std::string label, std::size_t total, bool quiet)
    : label_(std::move(label)),
      total_(total),
      quiet_(quiet),
      start_(std::chrono::steady_clock::now()) {}

double ItemProgress::elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ItemProgress::update(std::size_t done) {
    const std::size_t tenth = total_ / 10 > 0 ? total_ / 10 : 1;
    if (quiet_ || done == 0 || (!line_.live() && done != total_ && done % tenth != 0)) {
        return;
    }
    const double elapsed = elapsedSeconds();
    char line[200];
    std::snprintf(line, sizeof line, "%s %zu/%zu  %.0f ms each  elapsed %s  ETA %s", label_.c_str(),
                  done, total_, 1000 * elapsed / double(done), formatDuration(elapsed).c_str(),
                  formatDuration(elapsed * double(total_ - done) / double(done)).c_str());
    line_.show(line);
}

void ItemProgress::finish() { line_.finish(); }

}  // namespace weir
