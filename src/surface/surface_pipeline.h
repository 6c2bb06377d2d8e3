// Surface reconstruction as a short list of stages over one backend's primitives (CpuExec or
// CudaExec): bin the particles, flag the lattice blocks near them (sparse_lattice.h), sample the
// field in those blocks, number the cut edges by a prefix sum, place their vertices, count each
// cell's triangles, prefix sum, write the triangles. The prefix sums fix every vertex's and
// triangle's slot, so both backends give the same mesh in the same order.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <future>
#include <string>
#include <type_traits>
#include <vector>

#include "core/stage_timer.h"
#include "grid/cell_id.h"
#include "grid/dense_grid.h"
#include "surface/anisotropy.h"
#include "surface/marching_cubes.h"
#include "surface/sparse_lattice.h"
#include "surface/surface.h"
#include "surface/surface_field.h"

namespace weir {

template <class Exec, class T>
using ExecBuffer = typename Exec::template Buffer<T>;

// The sparse lattice's working arrays: block flags and their numbering, the field's samples, the
// per-slot prefix sums of vertices and triangles.
template <class Exec>
struct SurfaceScratch {
    ExecBuffer<Exec, std::int32_t> flags, blockEnd, blockSlot, keptBlock;
    ExecBuffer<Exec, float> values;
    ExecBuffer<Exec, std::int64_t> vertexEnd, triangleEnd;
};

// A mesh left in the backend's memory (the GPU's for CudaExec): what marching cubes writes, the
// counts on the host, and the working arrays that made it. Buffers only grow, so a mesh rebuilt
// every frame (the live water look) allocates only when the fluid's surface grows.
template <class Exec>
struct BackendMesh {
    ExecBuffer<Exec, Vec3f> positions, normals;  // vertexCount each
    ExecBuffer<Exec, std::uint32_t> indices;     // 3 * triangleCount
    std::int64_t vertexCount = 0, triangleCount = 0;
    SurfaceScratch<Exec> scratch;
};

// Told each count as soon as marching cubes knows it (the host path allocates its arrays on
// other threads meanwhile); this one does nothing.
struct IgnoreMeshCounts {
    void vertices(std::int64_t) {}
    void triangles(std::int64_t) {}
};

// Marching cubes over a field already sampled on the backend (a SampledFieldView or a
// SparseFieldView whose arrays live there): each slot's cut edges, a prefix sum that numbers
// their vertices, each cell's triangle count from its case, a prefix sum, the triangles. A cell
// belongs to the slot of its lowest corner. Counts are 64-bit: a lattice of up to 2^31 samples
// has up to 3 * 2^31 cut edges. The mesh stays in the backend's memory, in `out`.
template <class Exec, class Lattice, class Counts>
void marchingCubesInto(Exec& exec, const Lattice& lattice, BackendMesh<Exec>& out, Counts& counts) {
    const Index slots = Index(lattice.slotCount());
    exec.stageBegin("surface vertices");
    ExecBuffer<Exec, std::int64_t>& vertexEnd = out.scratch.vertexEnd;
    vertexEnd.resize(static_cast<std::size_t>(slots));
    {
        std::int64_t* end = vertexEnd.data();
        exec.forEach(slots, [=] WEIR_HD(Index i) {
            int x, y, z;
            end[i] =
                lattice.slotSample(i, x, y, z) ? bitCount3(cutEdgesOfSample(lattice, x, y, z)) : 0;
        });
        exec.inclusiveScan(end, end, slots);
    }
    const std::int64_t vertexCount = exec.readOne(vertexEnd, std::size_t(slots - 1));
    if (vertexCount > kMaxSurfaceVertices) {
        throw SurfaceError("the surface has " + std::to_string(vertexCount) +
                           " vertices, more than a mesh's 32-bit indices allow (" +
                           std::to_string(kMaxSurfaceVertices) + "); use a larger cell size");
    }
    counts.vertices(vertexCount);
    out.vertexCount = vertexCount;
    out.positions.resize(static_cast<std::size_t>(vertexCount));
    out.normals.resize(static_cast<std::size_t>(vertexCount));
    ExecBuffer<Exec, Vec3f>& positions = out.positions;
    ExecBuffer<Exec, Vec3f>& normals = out.normals;
    {
        const std::int64_t* end = vertexEnd.data();
        Vec3f* positionOut = positions.data();
        Vec3f* normalOut = normals.data();
        exec.forEach(slots, [=] WEIR_HD(Index i) {
            int x, y, z;
            if (!lattice.slotSample(i, x, y, z)) {
                return;
            }
            const int mask = cutEdgesOfSample(lattice, x, y, z);
            std::int64_t v = end[i] - bitCount3(mask);
            for (int axis = 0; axis < 3; ++axis) {
                if ((mask >> axis) & 1) {
                    edgeVertex(lattice, x, y, z, axis, positionOut[v], normalOut[v]);
                    ++v;
                }
            }
        });
    }
    exec.stageEnd("surface vertices");

    exec.stageBegin("surface triangles");
    ExecBuffer<Exec, std::uint8_t> tableCounts, tableEdges;
    exec.upload(tableCounts, kMarchingCubesTable.triangleCount.data(), 256);
    exec.upload(tableEdges, kMarchingCubesTable.triangleEdges[0].data(),
                256 * 3 * kMaxTrianglesPerCube);
    const MarchingCubesTableView table{tableCounts.data(), tableEdges.data()};
    ExecBuffer<Exec, std::int64_t>& triangleEnd = out.scratch.triangleEnd;
    triangleEnd.resize(static_cast<std::size_t>(slots));
    {
        std::int64_t* end = triangleEnd.data();
        exec.forEach(slots, [=] WEIR_HD(Index i) {
            int x, y, z;
            const bool cell = lattice.slotSample(i, x, y, z) && x + 1 < lattice.nx &&
                              y + 1 < lattice.ny && z + 1 < lattice.nz;
            end[i] = cell ? table.triangleCount[cubeCase(lattice, x, y, z)] : 0;
        });
        exec.inclusiveScan(end, end, slots);
    }
    const std::int64_t triangleCount = exec.readOne(triangleEnd, std::size_t(slots - 1));
    counts.triangles(triangleCount);
    out.triangleCount = triangleCount;
    out.indices.resize(3 * static_cast<std::size_t>(triangleCount));
    ExecBuffer<Exec, std::uint32_t>& indices = out.indices;
    {
        const std::int64_t* end = triangleEnd.data();
        const std::int64_t* verticesEnd = vertexEnd.data();
        std::uint32_t* out = indices.data();
        exec.forEach(slots, [=] WEIR_HD(Index i) {
            int x, y, z;
            if (!lattice.slotSample(i, x, y, z) || x + 1 >= lattice.nx || y + 1 >= lattice.ny ||
                z + 1 >= lattice.nz) {
                return;
            }
            const int cubeCaseBits = cubeCase(lattice, x, y, z);
            const std::int64_t first = end[i] - table.triangleCount[cubeCaseBits];
            cellTriangles(lattice, table, verticesEnd, x, y, z, cubeCaseBits, out + 3 * first);
        });
    }
    exec.stageEnd("surface triangles");
}

// The host's mesh arrays, allocated and zeroed on threads of their own while the device works
// (at 1e8 particles that is 650 MB, a quarter of a second on one core).
struct HostMeshAllocation {
    TriangleMesh* mesh;
    std::future<void> positionsReady, normalsReady, indicesReady;

    void vertices(std::int64_t count) {
        TriangleMesh* m = mesh;
        positionsReady = std::async(std::launch::async, [m, count] {
            m->positions.resize(static_cast<std::size_t>(count));
        });
        normalsReady = std::async(
            std::launch::async, [m, count] { m->normals.resize(static_cast<std::size_t>(count)); });
    }
    void triangles(std::int64_t count) {
        TriangleMesh* m = mesh;
        indicesReady = std::async(std::launch::async, [m, count] {
            m->indices.resize(3 * static_cast<std::size_t>(count));
        });
    }
};

// Marching cubes (marchingCubesInto), the mesh then downloaded to the host.
template <class Exec, class Lattice>
TriangleMesh marchingCubes(Exec& exec, const Lattice& lattice) {
    TriangleMesh mesh;
    HostMeshAllocation allocation{&mesh, {}, {}, {}};
    BackendMesh<Exec> out;
    marchingCubesInto(exec, lattice, out, allocation);

    exec.stageBegin("surface download");
    allocation.positionsReady.get();
    allocation.normalsReady.get();
    allocation.indicesReady.get();
    exec.download(out.positions, mesh.positions.data(), mesh.positions.size());
    exec.download(out.normals, mesh.normals.data(), mesh.normals.size());
    exec.download(out.indices, mesh.indices.data(), mesh.indices.size());
    exec.stageEnd("surface download");
    return mesh;
}

// What sparseSurface does with the sampled lattice: marching cubes to a host mesh (returned) ...
template <class Exec>
struct MarchToHost {
    using Result = TriangleMesh;
    Exec* exec;
    template <class Lattice>
    TriangleMesh operator()(const Lattice& lattice) const {
        return marchingCubes(*exec, lattice);
    }
    SurfaceScratch<Exec>* scratch() const { return nullptr; }  // sparseSurface's own
};

// ... or into a mesh left in the backend's memory (returns the triangle count).
template <class Exec>
struct MarchInto {
    using Result = std::int64_t;
    Exec* exec;
    BackendMesh<Exec>* out;
    template <class Lattice>
    std::int64_t operator()(const Lattice& lattice) const {
        IgnoreMeshCounts counts;
        marchingCubesInto(*exec, lattice, *out, counts);
        return out->triangleCount;
    }
    SurfaceScratch<Exec>* scratch() const { return &out->scratch; }  // kept with the mesh
};

// The field at every sample of the dense lattice (tests compare the sparse lattice with it),
// snapped off the iso-value by `snap` (snappedOffIso).
template <class Exec, class Field>
void sampleField(Exec& exec, const Field& field, const SampledFieldView& lattice, float* out,
                 float snap) {
    exec.forEach(Index(lattice.slotCount()), [=] WEIR_HD(Index i) {
        int x, y, z;
        lattice.slotSample(i, x, y, z);
        const Vec3 at = lattice.origin + Vec3(Real(x), Real(y), Real(z)) * lattice.cellSize;
        out[i] = snappedOffIso(field.valueAt(at), lattice.iso, snap);
    });
}

// The field's surface over the sparse lattice (sparse_lattice.h): the blocks within the field's
// reach of the n points flagged, numbered by a prefix sum, the field sampled in the kept blocks
// only, then marched by march(lattice) (MarchToHost, MarchInto), whose result it returns.
// Refused (SurfaceError) where the kept samples pass the plan's limit or, without one, half the
// backend's free memory (`memoryName` names it in the message).
// (The functions with device lambdas name their result types: nvcc does not allow a deduced one.)
template <class Exec, class Field, class March>
typename March::Result sparseSurface(Exec& exec, const Field& field, const Real4* points, Index n,
                                     const SurfacePlan& plan, const char* memoryName,
                                     const March& march) {
    exec.stageBegin("surface blocks");
    const LatticeBlocks blocks = LatticeBlocks::of(plan.dims[0], plan.dims[1], plan.dims[2]);
    const Index blockCount = Index(blocks.count());  // planSurface keeps it under 2^28
    SurfaceScratch<Exec> ownScratch;
    SurfaceScratch<Exec>& scratch = march.scratch() != nullptr ? *march.scratch() : ownScratch;
    ExecBuffer<Exec, std::int32_t>& flags = scratch.flags;
    ExecBuffer<Exec, std::int32_t>& blockEnd = scratch.blockEnd;
    flags.resize(static_cast<std::size_t>(blockCount));
    blockEnd.resize(static_cast<std::size_t>(blockCount));
    std::int32_t* flag = flags.data();
    exec.forEach(blockCount, [=] WEIR_HD(Index b) { flag[b] = 0; });
    // The field's kernels reach R from the points; two cells more keep the lowest corner of every
    // cell and edge with a sample in reach in a kept block, float rounding included.
    const Real reach = Real(plan.kernelRadius + 2 * plan.cellSize);
    const Vec3 origin(plan.origin);
    const Real cellSize = Real(plan.cellSize);
    exec.forEach(n, [=] WEIR_HD(Index i) {
        flagBlocksNear(points[i].xyz(), reach, origin, cellSize, blocks, flag);
    });
    exec.inclusiveScan(flag, blockEnd.data(), blockCount);
    const std::int64_t kept = exec.readOne(blockEnd, std::size_t(blockCount - 1));
    const std::int64_t samples = kept * kSurfaceBlockSamples;
    const bool limitGiven = plan.maxSamples > 0;
    const std::int64_t limit =
        limitGiven
            ? plan.maxSamples
            : std::min<std::int64_t>(kMaxSurfaceSamples, std::int64_t(exec.freeMemoryBytes() / 2 /
                                                                      kBytesPerSurfaceSample));
    if (samples > limit) {
        throw SurfaceError(surfaceTooLargeMessage(plan, samples, limit, limitGiven, memoryName));
    }
    ExecBuffer<Exec, std::int32_t>& blockSlot = scratch.blockSlot;
    ExecBuffer<Exec, std::int32_t>& keptBlock = scratch.keptBlock;
    blockSlot.resize(static_cast<std::size_t>(blockCount));
    keptBlock.resize(static_cast<std::size_t>(std::max<std::int64_t>(kept, 1)));
    {
        const std::int32_t* end = blockEnd.data();
        std::int32_t* slotOut = blockSlot.data();
        std::int32_t* keptOut = keptBlock.data();
        exec.forEach(blockCount, [=] WEIR_HD(Index b) {
            const bool isKept = flag[b] != 0;
            slotOut[b] = isKept ? end[b] - 1 : -1;
            if (isKept) {
                keptOut[end[b] - 1] = b;
            }
        });
    }
    exec.stageEnd("surface blocks");

    exec.stageBegin("surface field");
    ExecBuffer<Exec, float>& values = scratch.values;
    values.resize(static_cast<std::size_t>(samples));
    SparseFieldView lattice;
    lattice.values = values.data();
    lattice.blockSlot = blockSlot.data();
    lattice.keptBlock = keptBlock.data();
    lattice.keptCount = kept;
    lattice.blocks = blocks;
    lattice.iso = float(plan.iso);
    lattice.farValue = field.valueFarAway();
    lattice.nx = plan.dims[0];
    lattice.ny = plan.dims[1];
    lattice.nz = plan.dims[2];
    lattice.origin = origin;
    lattice.cellSize = cellSize;
    {
        float* out = values.data();
        const float snap = float(plan.snapMargin);
        exec.forEach(Index(samples), [=] WEIR_HD(Index i) {
            int x, y, z;
            out[i] =
                lattice.slotSample(i, x, y, z)
                    ? snappedOffIso(field.valueAt(lattice.origin + Vec3(Real(x), Real(y), Real(z)) *
                                                                       lattice.cellSize),
                                    lattice.iso, snap)
                    : lattice.farValue;
        });
    }
    exec.stageEnd("surface field");
    return march(lattice);
}

template <class Exec, class Field>
TriangleMesh sparseSurface(Exec& exec, const Field& field, const Real4* points, Index n,
                           const SurfacePlan& plan, const char* memoryName) {
    return sparseSurface(exec, field, points, n, plan, memoryName, MarchToHost<Exec>{&exec});
}

// The isotropic field of the plan over particles binned on the backend.
inline ZhuBridsonField isotropicField(const SurfacePlan& plan, const ParticleBinsView& binned) {
    ZhuBridsonField field;
    field.particles = binned;
    field.kernelRadius2 = Real(plan.kernelRadius * plan.kernelRadius);
    field.inverseKernelRadius2 = Real(1 / (plan.kernelRadius * plan.kernelRadius));
    field.particleRadius = Real(plan.particleRadius);
    field.inverseSpacing = Real(1 / plan.spacing);
    field.farValue = Real((plan.kernelRadius - plan.particleRadius) / plan.spacing);
    return field;
}

// Meshes a field by sparseSurface: what withSurfaceField hands the field to. (A functor, not a
// lambda: nvcc does not let a host lambda's type name a __device__ lambda's template argument.)
template <class Exec, class March = MarchToHost<Exec>>
struct SparseSurfaceBuild {
    Exec* exec;
    const SurfacePlan* plan;
    const char* memoryName;
    March march;
    using Result = typename March::Result;

    template <class Field>
    Result operator()(const Field& field, const Real4* points, Index n) const {
        return sparseSurface(*exec, field, points, n, *plan, memoryName, march);
    }
};

// Yu & Turk's anisotropic kernels: each particle's smoothed centre and matrix, then the centres
// binned again (they moved by up to lambda R) with their matrices in the new order; their field
// and centres go to build(field, centres, n).
// What a field's build functor returns: its Result, else a host mesh.
template <class Build, class = void>
struct BuildResult {
    using type = TriangleMesh;
};
template <class Build>
struct BuildResult<Build, std::void_t<typename Build::Result>> {
    using type = typename Build::Result;
};

template <class Exec, class Build>
typename BuildResult<Build>::type withAnisotropicField(Exec& exec, const SurfacePlan& plan,
                                                       const ParticleBinsView& binned,
                                                       const GridSpec& binSpec, Index n,
                                                       const Build& build) {
    exec.stageBegin("surface anisotropy");
    const double neighbourhood = kAnisotropyNeighbourhood * plan.kernelRadius;
    AnisotropyParams params;
    params.radius2 = Real(neighbourhood * neighbourhood);
    params.inverseRadius = Real(1 / neighbourhood);
    params.inverseKernelRadius = Real(1 / plan.kernelRadius);
    params.smoothing = Real(kAnisotropySmoothing);
    params.maxStretch = Real(kAnisotropyMaxStretch);
    params.minNeighbours = kAnisotropyMinNeighbours;
    params.isotropicDeterminant = Real(1 / std::pow(plan.kernelRadius, 3));
    ExecBuffer<Exec, Real4> centres(static_cast<std::size_t>(n)),
        sortedCentres(static_cast<std::size_t>(n));
    ExecBuffer<Exec, SymmetricMatrix3> matrices(static_cast<std::size_t>(n)),
        sortedMatrices(static_cast<std::size_t>(n));
    {
        Real4* centreOut = centres.data();
        SymmetricMatrix3* matrixOut = matrices.data();
        ParticleBinsView wide = binned;
        wide.reach = int(std::ceil(neighbourhood / plan.binSize - 1e-9));
        exec.forEach(n, [=] WEIR_HD(Index i) {
            anisotropicKernelOf(i, wide, params, centreOut[i], matrixOut[i]);
        });
    }
    DenseGrid<Exec> centreBins(binSpec, 1);
    centreBins.build(exec, centres.data(), n);
    {
        const Index* permutation = centreBins.permutation();
        const Real4* centreIn = centres.data();
        const SymmetricMatrix3* matrixIn = matrices.data();
        Real4* centreOut = sortedCentres.data();
        SymmetricMatrix3* matrixOut = sortedMatrices.data();
        exec.forEach(n, [=] WEIR_HD(Index k) {
            centreOut[k] = centreIn[permutation[k]];
            matrixOut[k] = matrixIn[permutation[k]];
        });
    }
    AnisotropicField field;
    field.centres = {centreBins.cells(), sortedCentres.data(), binned.reach};
    field.matrix = sortedMatrices.data();
    field.kernelRadius2 = Real(plan.kernelRadius * plan.kernelRadius);
    field.weightScale = Real(std::pow(plan.spacing, 3) * 315 / (64 * 3.14159265358979323846));
    field.threshold = Real(plan.fractionThreshold);
    field.inverseSlope = Real(1 / plan.fractionSlope);
    exec.stageEnd("surface anisotropy");
    return build(field, sortedCentres.data(), n);
}

// The plan's field over n particles already in the backend's memory (x, y, z; w unused): bins,
// then (anisotropic) the kernels; returns build(field, points, n), with points the particles or
// the kernels' centres, from which the field reaches R.
template <class Exec, class Build>
typename BuildResult<Build>::type withSurfaceFieldAt(Exec& exec, const Real4* pos, Index n,
                                                     const SurfacePlan& plan, const Build& build) {
    ExecBuffer<Exec, Real4> sortedPos(static_cast<std::size_t>(n));
    // Particles into bins of at least R / 2 (the dense cell table of grid/dense_grid.h).
    exec.stageBegin("surface bins");
    const Vec3d binExtent = plan.particleMax - plan.particleMin;
    const GridSpec binSpec = makeGridSpec(
        plan.particleMin, plan.particleMin + binExtent + Vec3d(1, 1, 1) * (1e-6 * plan.binSize),
        plan.binSize, 1 << 21);
    DenseGrid<Exec> bins(binSpec, 1);
    bins.build(exec, pos, n);
    {
        const Index* permutation = bins.permutation();
        const Real4* unsorted = pos;
        Real4* sorted = sortedPos.data();
        exec.forEach(n, [=] WEIR_HD(Index k) { sorted[k] = unsorted[permutation[k]]; });
    }
    const ParticleBinsView binned{bins.cells(), sortedPos.data(),
                                  int(std::ceil(plan.kernelRadius / plan.binSize - 1e-9))};
    exec.stageEnd("surface bins");

    if (plan.field == SurfaceField::Isotropic) {
        return build(isotropicField(plan, binned), sortedPos.data(), n);
    }
    return withAnisotropicField(exec, plan, binned, binSpec, n, build);
}

// The same over host particles, uploaded first.
template <class Exec, class Build>
typename BuildResult<Build>::type withSurfaceField(Exec& exec, const HostParticles& particles,
                                                   const SurfacePlan& plan, const Build& build) {
    const Index n = Index(particles.size());

    exec.stageBegin("surface upload");
    ExecBuffer<Exec, Real4> pos(static_cast<std::size_t>(n));
    {
        ExecBuffer<Exec, Real> x, y, z;
        exec.upload(x, particles.x.data(), particles.x.size());
        exec.upload(y, particles.y.data(), particles.y.size());
        exec.upload(z, particles.z.data(), particles.z.size());
        const Real* px = x.data();
        const Real* py = y.data();
        const Real* pz = z.data();
        Real4* out = pos.data();
        exec.forEach(n, [=] WEIR_HD(Index i) { out[i] = {px[i], py[i], pz[i], Real(0)}; });
    }
    exec.stageEnd("surface upload");
    return withSurfaceFieldAt(exec, pos.data(), n, plan, build);
}

// Particles to mesh: bins, (anisotropic kernels), blocks, field, marching cubes; each stage's
// time into `stages` where given. `memoryName` names the backend's memory in messages.
template <class Exec>
TriangleMesh extractSurface(Exec& exec, const HostParticles& particles, const SurfacePlan& plan,
                            const char* memoryName, StageTimes* stages = nullptr) {
    exec.timing = stages != nullptr;
    TriangleMesh mesh = withSurfaceField(
        exec, particles, plan, SparseSurfaceBuild<Exec>{&exec, &plan, memoryName, {&exec}});
    if (stages != nullptr) {
        exec.collectTimes(*stages);
    }
    return mesh;
}

// Particles already in the backend's memory (n of them at `points`, e.g. a CUDA solver's
// positions) to a mesh left there, in `out`: the stages of extractSurface without the upload and
// the download, and without removing slivers (a host step). Returns the triangle count.
template <class Exec>
std::int64_t extractSurfaceInto(Exec& exec, const Real4* points, Index n, const SurfacePlan& plan,
                                const char* memoryName, BackendMesh<Exec>& out,
                                StageTimes* stages = nullptr) {
    exec.timing = stages != nullptr;
    const std::int64_t triangles = withSurfaceFieldAt(
        exec, points, n, plan,
        SparseSurfaceBuild<Exec, MarchInto<Exec>>{&exec, &plan, memoryName, {&exec, &out}});
    if (stages != nullptr) {
        exec.collectTimes(*stages);
    }
    return triangles;
}

}  // namespace weir
