// Drives the steps of a simulation: advancing to an output time in batches, with the clock
// (physics/time_step.h) on the device and read back once per batch, and replaying steps as a
// CUDA graph where the step allows it. It knows nothing of what a step does.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/config.h"
#include "physics/time_step.h"

namespace weir {

template <class Exec>
class StepDriver {
   public:
    template <class T>
    using Buffer = typename Exec::template Buffer<T>;

    static constexpr double kNoTarget = 1e300;

    // The clock at the start: time 0, the largest initial speed and acceleration (for the first
    // dt), and a first guess of the typical step.
    void start(Exec& exec, double maxSpeed2, double maxAccel2, double typicalStep) {
        StepClock clock{};
        clock.time = 0;
        clock.target = kNoTarget;
        clock.maxSpeed2 = floatBits(float(maxSpeed2));
        clock.maxAccel2 = floatBits(float(maxAccel2));
        exec.upload(clock_, &clock, 1);
        typicalStep_ = typicalStep;
    }

    // The clock in device memory, for the stages.
    StepClock* clock() { return clock_.data(); }
    const Buffer<StepClock>& buffer() const { return clock_; }
    StepClock read(Exec& exec) const { return exec.readOne(clock_, 0); }
    void write(Exec& exec, const StepClock& clock) { exec.writeOne(clock_, 0, clock); }

    // Steps until the clock reaches `target`: batches of the steps the last batches' mean dt
    // predicts, the clock read back after each (one host round trip per batch, not per step).
    // Steps past the target inside a batch are no-ops that cost only the grid build. Stops early
    // when faulted() says the run blew up. step(): one step; capturable: whether steps may be
    // replayed as a graph.
    template <class Step, class Faulted>
    void advanceTo(Exec& exec, double target, Step&& step, bool capturable, Faulted&& faulted) {
        StepClock clock = read(exec);
        clock.target = target;
        write(exec, clock);
        targetSet_ = true;
        while (clock.time < target) {
            const double wanted = std::ceil((target - clock.time) / typicalStep_ - 1e-6);
            const int batch = int(std::clamp(wanted, 1.0, 1e6));
            const double before = clock.time;
            const int stepsBefore = clock.step;
            run(exec, batch, step, capturable);
            clock = read(exec);
            if (faulted() || !(clock.time > before)) {
                break;  // blown up (reported by fault()), or a step that cannot advance
            }
            if (!clock.landing || clock.step - stepsBefore > 1) {
                typicalStep_ = (clock.time - before) / double(clock.step - stepsBefore);
            }
        }
    }

    // `steps` plain steps: no output time to stop on.
    template <class Step>
    void advance(Exec& exec, int steps, Step&& step, bool capturable) {
        if (targetSet_) {
            StepClock clock = read(exec);
            clock.target = kNoTarget;
            write(exec, clock);
            targetSet_ = false;
        }
        run(exec, steps, step, capturable);
    }

    // `steps` steps, replayed as a CUDA graph of two steps where allowed. Stage timing reads
    // events after each stage, which a graph cannot.
    template <class Step>
    void run(Exec& exec, int steps, Step&& step, bool capturable) {
        auto counted = [&] {
            step();
            ++calls_;
        };
        if constexpr (Exec::isDevice) {
            if (capturable && !exec.timing && steps >= 4) {
                if (!graph_.ready()) {
                    counted();  // allocates every buffer: a capture cannot allocate
                    --steps;
                    graphParity_ = int(calls_ & 1);
                    exec.capture(graph_, [&] {
                        step();
                        step();
                    });
                }
                // The graph holds the buffer swaps of a pair of steps, so it starts on a call of
                // the parity it was captured at.
                if (int(calls_ & 1) != graphParity_) {
                    counted();
                    --steps;
                }
                for (; steps >= 2; steps -= 2) {
                    exec.launch(graph_);
                    calls_ += 2;
                }
            }
        }
        for (; steps > 0; --steps) {
            counted();
        }
    }

   private:
    Buffer<StepClock> clock_;
    typename Exec::Graph graph_;
    int graphParity_ = 0;
    long long calls_ = 0;     // steps run, no-op steps included (graph parity)
    double typicalStep_ = 0;  // mean dt of the last batch, to size the next
    bool targetSet_ = false;
};

}  // namespace weir
