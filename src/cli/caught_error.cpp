// The one place where a command turns the exception it caught into a message and an exit code.
#include <exception>
#include <iostream>
#include <new>
#include <stdexcept>

#include "cli/commands.h"
#include "cluster/communicator.h"

namespace weir {

CaughtError caughtError() {
    try {
        throw;
    } catch (const std::invalid_argument& e) {
        return {e.what(), kExitUsage};
    } catch (const std::bad_alloc&) {
        return {
            "out of memory: an allocation failed (std::bad_alloc), most likely the particles "
            "or the frames of a run too large for this machine; try fewer particles "
            "(--particles, particles.count), a larger particles.spacing, a smaller container, "
            "or close other programs",
            kExitError};
    } catch (const std::exception& e) {
        return {e.what(), kExitError};
    } catch (...) {
        return {"unknown error", kExitError};
    }
}

int reportCaughtError(const std::string& prefix) {
    const CaughtError error = caughtError();
    std::cerr << prefix << ": error: " << error.what << "\n";
    return error.exitCode;
}

int reportCaughtError(Communicator& comm) {
    if (comm.size() > 1) {
        // The other ranks may be waiting for this one in a collective: end them all.
        const CaughtError error = caughtError();
        std::cerr << "weir: " << comm.where() << ": error: " << error.what
                  << "\nweir: ending all ranks; frames already written are complete.\n";
        comm.abort(error.exitCode);
    }
    return reportCaughtError();
}

}  // namespace weir
