// Ctrl-C (SIGINT) and SIGTERM during `weir run`: a flag the run checks between frames, so that
// the frames already handed to the writer are written before the run ends.
#pragma once

namespace weir {

// While one exists, SIGINT and SIGTERM set the stop flag instead of ending the process; a second
// signal ends it at once, as without the guard (the default action is restored after the first).
// A signal ignored when the guard is made (nohup, a shell's background job) stays ignored. The
// destructor restores the handlers there were before. The stop flag is cleared when a guard is
// made and when it ends. Not for a distributed run (every rank would have to agree on where to
// stop).
class InterruptGuard {
   public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;
};

// The signal that asked the run to stop (SIGINT, SIGTERM), 0 when none did.
int stopSignal();
// Whether the run was asked to stop, by a signal or by requestStop().
bool stopRequested();
// Asks the run under the current guard to stop as a signal would, without one (tests, embedding
// code).
void requestStop();
// Clears the flag.
void clearStopRequest();

}  // namespace weir
