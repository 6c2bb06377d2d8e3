// BackgroundFrameWriter: a FrameWriter on a thread of its own, fed through a bounded pool of host
// frames, so that a run's frames are formatted and written while the simulation steps on.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "io/frame_writer.h"
#include "solver/particles.h"

namespace weir {

// How a run's frames reach the disk.
enum class FrameOutputMode {
    Background,  // formatted and written on a writer thread while the simulation steps on
    Foreground,  // written before the simulation steps on (weir before issue 17, for A/B runs)
    Off,         // not written at all (to time the stepping alone)
};

// WEIR_FRAME_OUTPUT: "background" (or unset), "foreground" or "off"; anything else throws
// std::invalid_argument naming the value and the allowed ones.
FrameOutputMode frameOutputModeFromEnvironment();

// How many frames of frameBytes each a run may hold on the host at once (being filled, queued,
// being written): at most `wanted`, at least 1, and together no more than half of availableBytes
// (the rest is the page cache's that the writes go through, and everything else's).
int framesThatFit(std::size_t frameBytes, std::size_t availableBytes, int wanted = 3);
// The host memory free for use now (MemAvailable), bytes.
std::size_t availableHostBytes();

// The stepping thread takes a free frame (acquire), fills it, hands it over (submit) and steps on;
// the writer thread writes the frames in the order handed over, each frame file then the .pvd
// and frames.json (FrameWriter, atomic renames as before), and returns the frame to the pool.
// At most `frames` frames exist: acquire waits while all are queued or being written, so a slow
// disk slows the run instead of filling memory. A frame handed over is always written, also when
// the run stops early (a blow-up, an exception, Ctrl-C): finish() and the destructor wait for
// the queue to drain. The first write error stops the writer (frames.json keeps the frames
// written before it) and is thrown again on the stepping thread by the next acquire, submit or
// finish.
class BackgroundFrameWriter {
   public:
    // frames >= 1 (else std::invalid_argument). Foreground: no thread, submit writes at once.
    BackgroundFrameWriter(std::unique_ptr<FrameWriter> writer, int frames,
                          FrameOutputMode mode = FrameOutputMode::Background);
    // Drains the queue (every frame handed over is written; errors are then dropped: finish()
    // reports them) and ends the thread.
    ~BackgroundFrameWriter();
    BackgroundFrameWriter(const BackgroundFrameWriter&) = delete;
    BackgroundFrameWriter& operator=(const BackgroundFrameWriter&) = delete;

    // A frame to fill, sized by whoever fills it; it returns to the pool when the last copy of
    // the pointer is gone. Waits while every frame is in use; throws a failed write's error.
    std::shared_ptr<HostParticles> acquire();
    // Hands a filled frame over to be written as frame `index` at simulation time `time`;
    // returns at once (Background). Throws a failed write's error, or this write's (Foreground).
    void submit(int index, double time, std::shared_ptr<const HostParticles> frame);
    // Waits until every frame handed over is written; throws the first write error.
    void finish();

    // Called on the writer thread about every `interval` while it has nothing to write (the
    // queue empty, every frame handed over written): e.g. to end the process on Ctrl-C once
    // nothing handed over can be lost. Set before the first submit.
    void setIdleCheck(std::function<void()> check, std::chrono::milliseconds interval);

    FrameWriter& writer() { return *writer_; }
    int capacity() const { return capacity_; }
    // The most frames that existed at once so far (the bound holds: <= capacity()).
    int peakFrames() const;
    // Frames written so far (listed in frames.json).
    int framesWritten() const;
    // The index of the frame written last, -1 before the first.
    int lastWrittenIndex() const;
    // What the writing cost so far: seconds spent writing (frame files and indexes), the bytes
    // of the frame files, and the seconds acquire() waited for a free frame (the run stalled).
    struct Stats {
        double writeSeconds = 0;
        std::uint64_t frameBytes = 0;
        double waitSeconds = 0;
    };
    Stats stats() const;

   private:
    struct Job {
        int index;
        double time;
        std::shared_ptr<const HostParticles> frame;
    };
    // The state both threads share, and the frames' deleters too (a frame may outlive its
    // writer): one mutex guards all of it.
    struct Shared {
        std::mutex mutex;
        std::condition_variable changed;  // a frame freed, a job done, an error, stop
        std::vector<std::unique_ptr<HostParticles>> frames;  // every frame made
        std::vector<HostParticles*> free;
        std::deque<Job> queue;
        bool busy = false;  // the writer thread is writing a job
        bool stop = false;
        std::exception_ptr error;
        int written = 0;
        int lastIndex = -1;
        int peak = 0;  // the most frames in use at once
        Stats stats;
    };

    void run();                           // the writer thread
    std::uint64_t write(const Job& job);  // one frame: its file's bytes; throws IoError

    std::unique_ptr<FrameWriter> writer_;
    int capacity_;
    FrameOutputMode mode_;
    std::shared_ptr<Shared> shared_;
    std::function<void()> idleCheck_;
    std::chrono::milliseconds idleInterval_{100};
    std::thread thread_;
};

}  // namespace weir
