// BackgroundFrameWriter: the frame pool, the queue and the writer thread.
#include "io/background_frame_writer.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/exec_cpu.h"

namespace weir {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

FrameOutputMode frameOutputModeFromEnvironment() {
    const char* text = std::getenv("WEIR_FRAME_OUTPUT");
    const std::string value = text != nullptr ? text : "";
    if (value.empty() || value == "background") {
        return FrameOutputMode::Background;
    }
    if (value == "foreground") {
        return FrameOutputMode::Foreground;
    }
    if (value == "off") {
        return FrameOutputMode::Off;
    }
    throw std::invalid_argument("WEIR_FRAME_OUTPUT=\"" + value +
                                "\" (allowed: background, foreground, off)");
}

int framesThatFit(std::size_t frameBytes, std::size_t availableBytes, int wanted) {
    const std::size_t fit = frameBytes > 0 ? availableBytes / 2 / frameBytes : std::size_t(wanted);
    return int(std::clamp<std::size_t>(fit, 1, std::size_t(std::max(wanted, 1))));
}

std::size_t availableHostBytes() { return CpuExec().freeMemoryBytes(); }

BackgroundFrameWriter::BackgroundFrameWriter(std::unique_ptr<FrameWriter> writer, int frames,
                                             FrameOutputMode mode)
    : writer_(std::move(writer)),
      capacity_(frames),
      mode_(mode),
      shared_(std::make_shared<Shared>()) {
    if (frames < 1) {
        throw std::invalid_argument("a frame writer needs room for at least 1 frame, got " +
                                    std::to_string(frames));
    }
    if (mode_ == FrameOutputMode::Off) {
        throw std::invalid_argument("a frame writer with frame output off");
    }
    if (mode_ == FrameOutputMode::Background) {
        thread_ = std::thread([this] { run(); });
    }
}

BackgroundFrameWriter::~BackgroundFrameWriter() {
    {
        std::lock_guard lock(shared_->mutex);
        shared_->stop = true;
    }
    shared_->changed.notify_all();
    if (thread_.joinable()) {
        thread_.join();  // the thread writes what is queued before it ends
    }
}

void BackgroundFrameWriter::setIdleCheck(std::function<void()> check,
                                         std::chrono::milliseconds interval) {
    std::lock_guard lock(shared_->mutex);
    idleCheck_ = std::move(check);
    idleInterval_ = interval;
}

std::shared_ptr<HostParticles> BackgroundFrameWriter::acquire() {
    const auto start = std::chrono::steady_clock::now();
    std::unique_lock lock(shared_->mutex);
    Shared& s = *shared_;
    for (;;) {
        if (s.error) {
            std::rethrow_exception(s.error);
        }
        if (!s.free.empty() || int(s.frames.size()) < capacity_) {
            break;
        }
        if (s.queue.empty() && !s.busy) {
            // Every frame is held by the caller: no write will free one.
            throw std::logic_error("BackgroundFrameWriter::acquire: all " +
                                   std::to_string(capacity_) +
                                   " frames are held outside the writer");
        }
        s.changed.wait(lock);
    }
    HostParticles* frame = nullptr;
    if (!s.free.empty()) {
        frame = s.free.back();
        s.free.pop_back();
    } else {
        s.frames.push_back(std::make_unique<HostParticles>());
        frame = s.frames.back().get();
    }
    s.peak = std::max(s.peak, int(s.frames.size() - s.free.size()));
    s.stats.waitSeconds += secondsSince(start);
    // Back to the pool with the last copy of the pointer, whichever thread drops it.
    std::shared_ptr<Shared> shared = shared_;
    return std::shared_ptr<HostParticles>(frame, [shared](HostParticles* p) {
        {
            std::lock_guard lock(shared->mutex);
            shared->free.push_back(p);
        }
        shared->changed.notify_all();
    });
}

void BackgroundFrameWriter::submit(int index, double time,
                                   std::shared_ptr<const HostParticles> frame) {
    if (mode_ == FrameOutputMode::Foreground) {
        const auto start = std::chrono::steady_clock::now();
        const std::uint64_t bytes = write({index, time, std::move(frame)});
        std::lock_guard lock(shared_->mutex);
        ++shared_->written;
        shared_->lastIndex = index;
        shared_->stats.writeSeconds += secondsSince(start);
        shared_->stats.frameBytes += bytes;
        return;
    }
    {
        std::lock_guard lock(shared_->mutex);
        if (shared_->error) {
            std::rethrow_exception(shared_->error);
        }
        shared_->queue.push_back({index, time, std::move(frame)});
    }
    shared_->changed.notify_all();
}

void BackgroundFrameWriter::finish() {
    std::unique_lock lock(shared_->mutex);
    shared_->changed.wait(lock, [&] { return shared_->queue.empty() && !shared_->busy; });
    if (shared_->error) {
        std::rethrow_exception(shared_->error);
    }
}

int BackgroundFrameWriter::peakFrames() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->peak;
}

int BackgroundFrameWriter::framesWritten() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->written;
}

BackgroundFrameWriter::Stats BackgroundFrameWriter::stats() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->stats;
}

std::uint64_t BackgroundFrameWriter::write(const Job& job) {
    writer_->write(job.index, job.time, *job.frame);
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(writer_->framePath(job.index), ec);
    return ec ? 0 : std::uint64_t(bytes);
}

int BackgroundFrameWriter::lastWrittenIndex() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->lastIndex;
}

void BackgroundFrameWriter::run() {
    Shared& s = *shared_;
    std::unique_lock lock(s.mutex);
    for (;;) {
        if (s.queue.empty()) {
            if (s.stop) {
                return;
            }
            if (!idleCheck_) {
                s.changed.wait(lock);
                continue;
            }
            const bool woken =
                s.changed.wait_for(lock, idleInterval_, [&] { return !s.queue.empty() || s.stop; });
            if (!woken) {
                const std::function<void()> check = idleCheck_;
                lock.unlock();
                check();  // nothing handed over is unwritten here
                lock.lock();
            }
            continue;
        }
        Job job = std::move(s.queue.front());
        s.queue.pop_front();
        if (s.error) {
            // After a failed write the frames handed over are dropped, not written; a frame
            // goes back to the pool under the lock, so not while holding it here.
            lock.unlock();
            job.frame.reset();
            lock.lock();
            s.changed.notify_all();
            continue;
        }
        s.busy = true;
        lock.unlock();
        std::exception_ptr error;
        const auto start = std::chrono::steady_clock::now();
        std::uint64_t bytes = 0;
        try {
            bytes = write(job);
        } catch (...) {
            error = std::current_exception();
        }
        const double seconds = secondsSince(start);
        job.frame.reset();  // back to the pool (takes the lock)
        lock.lock();
        s.busy = false;
        if (error) {
            s.error = error;
        } else {
            ++s.written;
            s.lastIndex = job.index;
            s.stats.writeSeconds += seconds;
            s.stats.frameBytes += bytes;
        }
        s.changed.notify_all();
    }
}

}  // namespace weir
