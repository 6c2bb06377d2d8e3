// The stop flag and the signal handlers that set it.
#include "cli/interrupt.h"

#include <signal.h>

#include <atomic>
#include <utility>

namespace weir {

namespace {

// Lock-free atomics are async-signal-safe to store to.
std::atomic<int> signalled{0};
std::atomic<bool> requested{false};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free);

struct sigaction previousInt, previousTerm;

extern "C" void onStopSignal(int signal) {
    signalled.store(signal);
    requested.store(true);
}

}  // namespace

InterruptGuard::InterruptGuard() {
    clearStopRequest();
    struct sigaction action {};
    action.sa_handler = onStopSignal;
    sigemptyset(&action.sa_mask);
    // A second signal takes the default action (ends the process); interrupted calls resume.
    action.sa_flags = SA_RESETHAND | SA_RESTART;
    for (auto [signal, previous] : {std::pair{SIGINT, &previousInt}, {SIGTERM, &previousTerm}}) {
        sigaction(signal, nullptr, previous);
        // A signal ignored from the start (nohup, a shell's background job) stays ignored.
        if (previous->sa_handler != SIG_IGN) {
            sigaction(signal, &action, nullptr);
        }
    }
}

InterruptGuard::~InterruptGuard() {
    clearStopRequest();
    sigaction(SIGINT, &previousInt, nullptr);
    sigaction(SIGTERM, &previousTerm, nullptr);
}

int stopSignal() { return signalled.load(); }
bool stopRequested() { return requested.load(); }
void requestStop() { requested.store(true); }
void clearStopRequest() {
    requested.store(false);
    signalled.store(0);
}

}  // namespace weir
