// A sparse surface lattice: the field lattice cut into blocks of 8 x 8 x 8 samples, of which only
// the blocks near some particle are stored. Every other sample lies beyond the field's reach from
// every particle, where the field takes its far value exactly, so a mesh marched over the sparse
// lattice is the dense lattice's mesh, while memory follows the fluid instead of its bounding box.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/atomics.h"
#include "core/config.h"
#include "core/vec3.h"

namespace weir {

constexpr int kSurfaceBlockShift = 3;
constexpr int kSurfaceBlockEdge = 1 << kSurfaceBlockShift;  // samples per block edge
constexpr int kSurfaceBlockSamples = kSurfaceBlockEdge * kSurfaceBlockEdge * kSurfaceBlockEdge;

// The block structure of a lattice of nx * ny * nz samples: blocks per axis.
struct LatticeBlocks {
    int nx = 0, ny = 0, nz = 0;  // samples per axis
    int bx = 0, by = 0, bz = 0;  // blocks per axis

    static WEIR_HD int blocksFor(int samples) {
        return (samples + kSurfaceBlockEdge - 1) >> kSurfaceBlockShift;
    }
    static LatticeBlocks of(int nx, int ny, int nz) {
        return {nx, ny, nz, blocksFor(nx), blocksFor(ny), blocksFor(nz)};
    }
    WEIR_HD std::int64_t count() const { return std::int64_t(bx) * by * std::int64_t(bz); }
    WEIR_HD std::int64_t blockOf(int x, int y, int z) const {
        return (std::int64_t(z >> kSurfaceBlockShift) * by + (y >> kSurfaceBlockShift)) *
                   std::int64_t(bx) +
               (x >> kSurfaceBlockShift);
    }
};

// Sets flags[b] = 1 for every block b holding a sample within `reach` of the point p (and some
// beyond: the blocks of the box of half-edge reach around p). The lattice's first sample is at
// `origin`, its samples `cellSize` apart.
WEIR_HD inline void flagBlocksNear(const Vec3& p, Real reach, const Vec3& origin, Real cellSize,
                                   const LatticeBlocks& blocks, std::int32_t* flags) {
    const int dims[3] = {blocks.nx, blocks.ny, blocks.nz};
    int first[3], last[3];
    for (int a = 0; a < 3; ++a) {
        const Real low = (p[a] - reach - origin[a]) / cellSize;
        const Real high = (p[a] + reach - origin[a]) / cellSize;
        // Clamped before the conversion to int: a point far outside the lattice flags nothing.
        const Real lowSample = std::fmax(std::ceil(low), Real(0));
        const Real highSample = std::fmin(std::floor(high), Real(dims[a] - 1));
        if (!(lowSample <= highSample)) {
            return;
        }
        first[a] = int(lowSample) >> kSurfaceBlockShift;
        last[a] = int(highSample) >> kSurfaceBlockShift;
    }
    for (int z = first[2]; z <= last[2]; ++z) {
        for (int y = first[1]; y <= last[1]; ++y) {
            for (int x = first[0]; x <= last[0]; ++x) {
                std::int32_t* flag =
                    flags + (std::int64_t(z) * blocks.by + y) * std::int64_t(blocks.bx) + x;
                atomicStoreFlag(flag, 1);
            }
        }
    }
}

// The lattice's kept blocks, each stored as kSurfaceBlockSamples samples (X fastest within the
// block), block after block; a sample of a dropped block reads farValue. The marching-cubes
// functions (marching_cubes.h) run over it as over the dense SampledFieldView.
struct SparseFieldView {
    const float* values;            // keptCount * kSurfaceBlockSamples samples
    const std::int32_t* blockSlot;  // per block of the lattice: its place among the kept, or -1
    const std::int32_t* keptBlock;  // per kept block: its index in the lattice
    std::int64_t keptCount;
    LatticeBlocks blocks;
    float iso;
    float farValue;  // the field beyond every particle's reach
    int nx, ny, nz;
    Vec3 origin;
    Real cellSize;

    WEIR_HD std::int64_t slotOf(int x, int y, int z) const {
        const std::int32_t block = blockSlot[blocks.blockOf(x, y, z)];
        if (block < 0) {
            return -1;
        }
        const int mask = kSurfaceBlockEdge - 1;
        return std::int64_t(block) * kSurfaceBlockSamples +
               ((((z & mask) << kSurfaceBlockShift) + (y & mask)) << kSurfaceBlockShift) +
               (x & mask);
    }
    WEIR_HD float value(int x, int y, int z) const {
        const std::int64_t slot = slotOf(x, y, z);
        return slot < 0 ? farValue : values[slot];
    }
    WEIR_HD std::int64_t slotCount() const { return keptCount * kSurfaceBlockSamples; }
    // The sample in slot i; false where the slot lies past the lattice's last sample (a block on
    // the lattice's high faces is partly outside it).
    WEIR_HD bool slotSample(std::int64_t i, int& x, int& y, int& z) const {
        const std::int64_t block = keptBlock[i >> (3 * kSurfaceBlockShift)];
        const int local = int(i & (kSurfaceBlockSamples - 1));
        const int mask = kSurfaceBlockEdge - 1;
        const std::int64_t blockX = block % blocks.bx, rest = block / blocks.bx;
        const std::int64_t blockY = rest % blocks.by, blockZ = rest / blocks.by;
        x = int(blockX << kSurfaceBlockShift) + (local & mask);
        y = int(blockY << kSurfaceBlockShift) + ((local >> kSurfaceBlockShift) & mask);
        z = int(blockZ << kSurfaceBlockShift) + (local >> (2 * kSurfaceBlockShift));
        return x < nx && y < ny && z < nz;
    }
};

}  // namespace weir
