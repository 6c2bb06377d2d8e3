// Marching cubes over a sampled field, as per-sample and per-cell functions that the CPU and the
// CUDA backends both run: cut edges and their vertices, cube cases and their triangles.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/config.h"
#include "core/vec3.h"
#include "surface/marching_cubes_tables.h"

namespace weir {

// A field sampled on a regular lattice of nx * ny * nz points, X fastest. A sample is inside the
// fluid where its value is below iso. Each sample owns the three lattice edges that leave it
// towards +X, +Y and +Z; an edge is cut where its ends lie on different sides.
//
// The functions below take any lattice view with this one's interface: value(x, y, z) at every
// sample of the lattice, and its samples stored in slots (slotCount() of them): slotOf(x, y, z)
// is a sample's slot, slotSample(i, ...) a slot's sample (false for a slot that holds none).
// This dense view stores every sample; SparseFieldView (sparse_lattice.h) only those near the
// fluid.
struct SampledFieldView {
    const float* values;
    float iso;
    int nx, ny, nz;
    Vec3 origin;
    Real cellSize;

    WEIR_HD std::int64_t slotOf(int x, int y, int z) const {
        return (std::int64_t(z) * ny + y) * std::int64_t(nx) + x;
    }
    WEIR_HD float value(int x, int y, int z) const { return values[slotOf(x, y, z)]; }
    WEIR_HD std::int64_t slotCount() const { return std::int64_t(nx) * ny * std::int64_t(nz); }
    WEIR_HD bool slotSample(std::int64_t i, int& x, int& y, int& z) const {
        x = int(i % nx);
        const std::int64_t rest = i / nx;
        y = int(rest % ny);
        z = int(rest / ny);
        return true;
    }
};

// A sample value within `margin` of iso moved out to iso -/+ margin, on the side it was on: the
// signs, and so the mesh's connectivity, stay as they were, but no cut edge's vertex comes closer
// to a sample than about margin over the field's change along the edge. Vertices near samples
// are what make marching cubes' slivers (needles and caps around the sample).
WEIR_HD inline float snappedOffIso(float value, float iso, float margin) {
    if (value < iso) {
        return value > iso - margin ? iso - margin : value;
    }
    return value < iso + margin ? iso + margin : value;
}

WEIR_HD inline int bitCount3(int mask) {
    return (mask & 1) + ((mask >> 1) & 1) + ((mask >> 2) & 1);
}

// Bit a set where the edge from sample (x, y, z) along axis a is cut.
template <class Lattice>
WEIR_HD int cutEdgesOfSample(const Lattice& f, int x, int y, int z) {
    const bool in = f.value(x, y, z) < f.iso;
    int mask = 0;
    if (x + 1 < f.nx && (f.value(x + 1, y, z) < f.iso) != in) {
        mask |= 1;
    }
    if (y + 1 < f.ny && (f.value(x, y + 1, z) < f.iso) != in) {
        mask |= 2;
    }
    if (z + 1 < f.nz && (f.value(x, y, z + 1) < f.iso) != in) {
        mask |= 4;
    }
    return mask;
}

// The field's gradient at a sample by central differences (one-sided on the lattice's faces),
// in field units per cell.
template <class Lattice>
WEIR_HD Vec3f sampleGradient(const Lattice& f, int x, int y, int z) {
    const int dims[3] = {f.nx, f.ny, f.nz};
    const float here = f.value(x, y, z);
    float g[3];
    for (int a = 0; a < 3; ++a) {
        int low[3] = {x, y, z}, high[3] = {x, y, z};
        --low[a];
        ++high[a];
        const bool hasLow = low[a] >= 0, hasHigh = high[a] < dims[a];
        const float highValue = hasHigh ? f.value(high[0], high[1], high[2]) : here;
        const float lowValue = hasLow ? f.value(low[0], low[1], low[2]) : here;
        g[a] = (highValue - lowValue) / float((hasLow ? 1 : 0) + (hasHigh ? 1 : 0));
    }
    return {g[0], g[1], g[2]};
}

// The vertex where the cut edge from sample (x, y, z) along `axis` crosses iso, by linear
// interpolation, and its unit normal from the interpolated gradient: out of the fluid, since
// the field grows outwards.
template <class Lattice>
WEIR_HD void edgeVertex(const Lattice& f, int x, int y, int z, int axis, Vec3f& position,
                        Vec3f& normal) {
    int end[3] = {x, y, z};
    end[axis] += 1;
    const float a = f.value(x, y, z), b = f.value(end[0], end[1], end[2]);
    const float t = (f.iso - a) / (b - a);  // in [0, 1]: a and b lie on different sides of iso
    const Vec3f ga = sampleGradient(f, x, y, z), gb = sampleGradient(f, end[0], end[1], end[2]);
    Vec3f g = ga + (gb - ga) * t;
    const float norm = length(g);
    if (norm > 0.0f) {
        normal = g / norm;
    } else {  // flat field: fall back to the edge, from its inside end to its outside end
        normal = Vec3f();
        normal[axis] = a < b ? 1.0f : -1.0f;
    }
    Vec3f local{float(x), float(y), float(z)};
    local[axis] += t;
    position = Vec3f(f.origin) + local * float(f.cellSize);
}

// The case of cell (x, y, z): bit c set where its corner c (marching_cubes_tables.h) is inside.
template <class Lattice>
WEIR_HD int cubeCase(const Lattice& f, int x, int y, int z) {
    int cubeCase = 0;
    for (int c = 0; c < 8; ++c) {
        const float v = f.value(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1));
        cubeCase |= v < f.iso ? (1 << c) : 0;
    }
    return cubeCase;
}

// The marching-cubes table where the running backend can read it.
struct MarchingCubesTableView {
    const std::uint8_t* triangleCount;  // 256 entries
    const std::uint8_t* triangleEdges;  // 256 * 3 * kMaxTrianglesPerCube entries
};

// Vertex numbering: the cut edges of sample s get the vertices firstVertex(s), firstVertex(s) + 1,
// ... in axis order, where vertexEnd is the inclusive prefix sum of the cut-edge counts of the
// samples, slot by slot.
template <class Lattice>
WEIR_HD std::int64_t edgeVertexIndex(const Lattice& f, const std::int64_t* vertexEnd, int x, int y,
                                     int z, int axis) {
    const int mask = cutEdgesOfSample(f, x, y, z);
    return vertexEnd[f.slotOf(x, y, z)] - bitCount3(mask) + bitCount3(mask & ((1 << axis) - 1));
}

// Writes the triangles of cell (x, y, z) as vertex indices, three per triangle, to out.
template <class Lattice>
WEIR_HD void cellTriangles(const Lattice& f, const MarchingCubesTableView& table,
                           const std::int64_t* vertexEnd, int x, int y, int z, int cubeCaseBits,
                           std::uint32_t* out) {
    const int count = table.triangleCount[cubeCaseBits];
    const std::uint8_t* edges = table.triangleEdges + cubeCaseBits * 3 * kMaxTrianglesPerCube;
    for (int k = 0; k < 3 * count; ++k) {
        const int edge = edges[k];
        const int start = cubeEdgeStart(edge);
        out[k] =
            std::uint32_t(edgeVertexIndex(f, vertexEnd, x + (start & 1), y + ((start >> 1) & 1),
                                          z + ((start >> 2) & 1), cubeEdgeAxis(edge)));
    }
}

}  // namespace weir
