// Backend dispatch, memory checks and fault diagnosis.
#include "solver/simulation.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/check.h"
#include "core/exec_cpu.h"
#include "grid/dense_grid.h"
#include "solver/methods.h"

namespace weir {

std::unique_ptr<Simulation> makeCpuSimulation(NeighbourMode mode, SimulationSetup setup);
#if defined(WEIR_HAS_CUDA)
std::unique_ptr<Simulation> makeCudaSimulation(NeighbourMode mode, SimulationSetup setup);
#endif

std::size_t bytesPerParticleEstimate(NeighbourMode mode, std::size_t cellIdBytes) {
    // Position and velocity (padded vectors, density in the velocity's fourth), id, pressure
    // term.
    std::size_t bytes = 2 * sizeof(Real4) + sizeof(Index) + sizeof(Real);
    switch (mode) {
        case NeighbourMode::Brute:
            bytes += sizeof(Real4);  // acceleration
            break;
        case NeighbourMode::Grid:
            // Acceleration; reorder scratch (position, velocity, id); keys and values twice for
            // the sort and as much again of sort scratch; the cell of each particle; cell tables
            // (id, start, count, 27 neighbours) for up to one occupied cell per two particles.
            bytes += 3 * sizeof(Real4) + sizeof(Index) + 2 * (2 * cellIdBytes + 2 * sizeof(Index)) +
                     sizeof(Index) + (cellIdBytes + 2 * sizeof(Index) + 27 * sizeof(Index)) / 2;
            break;
        default:
            // New state of the fused force pass (position, velocity), reorder scratch (id); key,
            // ticket and slot of the counting sort; dense bounds, at most 8 cells per particle.
            bytes += 2 * sizeof(Real4) + sizeof(Index) + sizeof(CellKey) + 2 * sizeof(Index) +
                     8 * sizeof(Index);
    }
    return bytes;
}

void checkMemoryFits(Index count, NeighbourMode mode, std::size_t freeBytes,
                     const std::string& where, std::size_t cellIdBytes) {
    const std::size_t perParticle = bytesPerParticleEstimate(mode, cellIdBytes);
    // Keep 10% and 256 MiB back for sort scratch, the driver and the rest of the process.
    const std::size_t reserve = (std::size_t(256) << 20) + freeBytes / 10;
    const std::size_t usable = freeBytes > reserve ? freeBytes - reserve : 0;
    const std::size_t fit = usable / perParticle;
    if (std::size_t(count) > fit) {
        std::ostringstream msg;
        msg << count << " particles need about " << (std::size_t(count) * perParticle >> 20)
            << " MiB (" << perParticle << " bytes each) but " << where << " has "
            << (freeBytes >> 20) << " MiB free: at most " << fit << " particles fit";
        throw SimulationError(msg.str());
    }
}

std::unique_ptr<Simulation> makeSimulation(Backend backend, NeighbourMode mode,
                                           SimulationSetup setup) {
    mode = resolveNeighbourMode(mode, setup.grid, setup.slotCount());
    if (setup.flow.active() && mode != NeighbourMode::Dense) {
        throw SimulationError(
            std::string("emitters and sinks run with the dense cell table only, ") +
            "but the neighbour search is '" + neighbourModeName(mode) +
            "'; use --neighbours dense (or auto, where the container's grid "
            "fits the dense table)");
    }
    try {
        setup.method = checkPressureSolver(setup.method);
    } catch (const std::invalid_argument& e) {
        throw SimulationError(e.what());
    }
    if (backend == Backend::Cpu) {
        checkMemoryFits(Index(setup.countHere()), mode, CpuExec().freeMemoryBytes(), "host memory",
                        cellIdBytesFor(setup.grid));
        return makeCpuSimulation(mode, std::move(setup));
    }
#if defined(WEIR_HAS_CUDA)
    if (!cudaDeviceAvailable()) {
        throw SimulationError("the cuda backend was asked for, but no CUDA device is visible");
    }
    return makeCudaSimulation(mode, std::move(setup));
#else
    throw SimulationError("the cuda backend was asked for, but this weir was built without CUDA");
#endif
}

std::string describeFault(const FaultRecord& fault, const SphParams& params) {
    std::ostringstream msg;
    msg << "the simulation blew up at step " << fault.step << " (t = " << fault.time << " s): ";
    switch (FaultCode(fault.code)) {
        case FaultCode::NotFinite:
            msg << "a particle's position or velocity became NaN or infinite";
            break;
        case FaultCode::TooFast:
            msg << "a particle reached " << fault.value << " m/s, past the bound of "
                << params.maxSpeed << " m/s";
            break;
        case FaultCode::Escaped:
            msg << "a particle left the container";
            break;
        case FaultCode::Compressed:
            msg << "a particle's density reached " << fault.value
                << " times the rest density, past the bound of " << params.maxDensityRatio
                << " (limits.maxCompression)";
            break;
        case FaultCode::Collapsed:
            msg << "particles collapsed onto one point (the kernel no longer pushes them apart)";
            break;
        default:
            msg << "unknown fault code " << fault.code;
    }
    if (fault.code != 0 && std::isfinite(fault.x) && std::isfinite(fault.y) &&
        std::isfinite(fault.z)) {
        msg << ", at (" << fault.x << ", " << fault.y << ", " << fault.z << ") m";
    }
    msg << ". Likely causes: a time step too large for the stiffness (CFL), too little viscosity,"
           " or a stiffness too low for the fall height; leave timeStep, stiffness and viscosity"
           " unset to have weir derive them.";
    return msg.str();
}

}  // namespace weir
