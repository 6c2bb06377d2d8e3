// Surface reconstruction as a short list of stages over one backend's primitives (CpuExec or
// CudaExec): bin the particles, sample the field, number the cut edges by a prefix sum, place
// their vertices, count each cell's triangles, prefix sum, write the triangles. The prefix sums
// fix every vertex's and triangle's slot, so both backends give the same mesh in the same order.
#pragma once

#include <cmath>
#include <vector>

#include "grid/cell_id.h"
#include "grid/dense_grid.h"
#include "surface/anisotropy.h"
#include "surface/marching_cubes.h"
#include "surface/surface.h"
#include "surface/surface_field.h"

namespace weir {

template <class Exec, class T>
using ExecBuffer = typename Exec::template Buffer<T>;

// Marching cubes over a field already sampled on the backend (lattice.values lives there).
template <class Exec>
TriangleMesh marchingCubes(Exec& exec, const SampledFieldView& lattice) {
    const Index samples = Index(lattice.nx) * Index(lattice.ny) * Index(lattice.nz);
    // Vertices: one per cut edge, numbered by a prefix sum over the samples owning the edges.
    ExecBuffer<Exec, Index> vertexEnd(static_cast<std::size_t>(samples));
    {
        Index* end = vertexEnd.data();
        exec.forEach(samples, [=] WEIR_HD(Index i) {
            int x, y, z;
            lattice.sampleCoords(i, x, y, z);
            end[i] = bitCount3(cutEdgesOfSample(lattice, x, y, z));
        });
        exec.inclusiveScan(end, end, samples);
    }
    const Index vertexCount = exec.readOne(vertexEnd, std::size_t(samples - 1));
    ExecBuffer<Exec, Vec3f> positions(static_cast<std::size_t>(vertexCount)),
        normals(static_cast<std::size_t>(vertexCount));
    {
        const Index* end = vertexEnd.data();
        Vec3f* positionOut = positions.data();
        Vec3f* normalOut = normals.data();
        exec.forEach(samples, [=] WEIR_HD(Index i) {
            int x, y, z;
            lattice.sampleCoords(i, x, y, z);
            const int mask = cutEdgesOfSample(lattice, x, y, z);
            Index v = end[i] - bitCount3(mask);
            for (int axis = 0; axis < 3; ++axis) {
                if ((mask >> axis) & 1) {
                    edgeVertex(lattice, x, y, z, axis, positionOut[v], normalOut[v]);
                    ++v;
                }
            }
        });
    }

    // Triangles: each cell's count from its case, a prefix sum, then each cell writes its own.
    ExecBuffer<Exec, std::uint8_t> tableCounts, tableEdges;
    exec.upload(tableCounts, kMarchingCubesTable.triangleCount.data(), 256);
    exec.upload(tableEdges, kMarchingCubesTable.triangleEdges[0].data(),
                256 * 3 * kMaxTrianglesPerCube);
    const MarchingCubesTableView table{tableCounts.data(), tableEdges.data()};
    const Index cells = lattice.cellCount();
    ExecBuffer<Exec, Index> triangleEnd(static_cast<std::size_t>(cells));
    {
        Index* end = triangleEnd.data();
        exec.forEach(cells, [=] WEIR_HD(Index c) {
            int x, y, z;
            lattice.cellCoords(c, x, y, z);
            end[c] = table.triangleCount[cubeCase(lattice, x, y, z)];
        });
        exec.inclusiveScan(end, end, cells);
    }
    const Index triangleCount = exec.readOne(triangleEnd, std::size_t(cells - 1));
    ExecBuffer<Exec, std::uint32_t> indices(3 * static_cast<std::size_t>(triangleCount));
    {
        const Index* end = triangleEnd.data();
        const Index* verticesEnd = vertexEnd.data();
        std::uint32_t* out = indices.data();
        exec.forEach(cells, [=] WEIR_HD(Index c) {
            int x, y, z;
            lattice.cellCoords(c, x, y, z);
            const int cubeCaseBits = cubeCase(lattice, x, y, z);
            const Index first = end[c] - table.triangleCount[cubeCaseBits];
            cellTriangles(lattice, table, verticesEnd, x, y, z, cubeCaseBits, out + 3 * first);
        });
    }

    TriangleMesh mesh;
    mesh.positions.resize(static_cast<std::size_t>(vertexCount));
    mesh.normals.resize(static_cast<std::size_t>(vertexCount));
    mesh.indices.resize(3 * static_cast<std::size_t>(triangleCount));
    exec.download(positions, mesh.positions.data(), mesh.positions.size());
    exec.download(normals, mesh.normals.data(), mesh.normals.size());
    exec.download(indices, mesh.indices.data(), mesh.indices.size());
    return mesh;
}

// The field at every lattice sample.
template <class Exec, class Field>
void sampleField(Exec& exec, const Field& field, const SampledFieldView& lattice, float* out) {
    const Index samples = Index(lattice.nx) * Index(lattice.ny) * Index(lattice.nz);
    exec.forEach(samples, [=] WEIR_HD(Index i) {
        int x, y, z;
        lattice.sampleCoords(i, x, y, z);
        const Vec3 at = lattice.origin + Vec3(Real(x), Real(y), Real(z)) * lattice.cellSize;
        out[i] = field.valueAt(at);
    });
}

// Particles to mesh: bins, field, marching cubes.
template <class Exec>
TriangleMesh extractSurface(Exec& exec, const HostParticles& particles, const SurfacePlan& plan) {
    const Index n = Index(particles.size());

    // Particles into bins of at least R / 2 (the dense cell table of grid/dense_grid.h).
    std::vector<Real4> hostPos(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) {
        hostPos[std::size_t(i)] = {particles.x[i], particles.y[i], particles.z[i], 0};
    }
    ExecBuffer<Exec, Real4> pos, sortedPos(static_cast<std::size_t>(n));
    exec.upload(pos, hostPos.data(), hostPos.size());
    const Vec3d binExtent = plan.particleMax - plan.particleMin;
    const GridSpec binSpec = makeGridSpec(
        plan.particleMin, plan.particleMin + binExtent + Vec3d(1, 1, 1) * (1e-6 * plan.binSize),
        plan.binSize, 1 << 21);
    DenseGrid<Exec> bins(binSpec, 1);
    bins.build(exec, pos.data(), n);
    {
        const Index* permutation = bins.permutation();
        const Real4* unsorted = pos.data();
        Real4* sorted = sortedPos.data();
        exec.forEach(n, [=] WEIR_HD(Index k) { sorted[k] = unsorted[permutation[k]]; });
    }
    const ParticleBinsView binned{bins.cells(), sortedPos.data(),
                                  int(std::ceil(plan.kernelRadius / plan.binSize - 1e-9))};

    const Index samples = Index(plan.sampleCount());
    ExecBuffer<Exec, float> values(static_cast<std::size_t>(samples));
    SampledFieldView lattice{values.data(), float(plan.iso),   plan.dims[0],       plan.dims[1],
                             plan.dims[2],  Vec3(plan.origin), Real(plan.cellSize)};
    if (plan.field == SurfaceField::Isotropic) {
        ZhuBridsonField field;
        field.particles = binned;
        field.kernelRadius2 = Real(plan.kernelRadius * plan.kernelRadius);
        field.inverseKernelRadius2 = Real(1 / (plan.kernelRadius * plan.kernelRadius));
        field.particleRadius = Real(plan.particleRadius);
        field.inverseSpacing = Real(1 / plan.spacing);
        field.farValue = Real((plan.kernelRadius - plan.particleRadius) / plan.spacing);
        sampleField(exec, field, lattice, values.data());
        return marchingCubes(exec, lattice);
    }

    // Anisotropic kernels: each particle's smoothed centre and matrix, then the centres binned
    // again (they moved by up to lambda R) with their matrices in the new order.
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
    sampleField(exec, field, lattice, values.data());
    return marchingCubes(exec, lattice);
}

}  // namespace weir
