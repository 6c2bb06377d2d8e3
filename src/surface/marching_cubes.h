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
struct SampledFieldView {
    const float* values;
    float iso;
    int nx, ny, nz;
    Vec3 origin;
    Real cellSize;

    WEIR_HD Index sampleIndex(int x, int y, int z) const {
        return (Index(z) * Index(ny) + Index(y)) * Index(nx) + Index(x);
    }
    WEIR_HD void sampleCoords(Index i, int& x, int& y, int& z) const {
        x = int(i % nx);
        const Index rest = i / nx;
        y = int(rest % ny);
        z = int(rest / ny);
    }
    WEIR_HD bool inside(Index i) const { return values[i] < iso; }
    WEIR_HD Index cellCount() const { return Index(nx - 1) * Index(ny - 1) * Index(nz - 1); }
    WEIR_HD void cellCoords(Index c, int& x, int& y, int& z) const {
        x = int(c % (nx - 1));
        const Index rest = c / (nx - 1);
        y = int(rest % (ny - 1));
        z = int(rest / (ny - 1));
    }
    WEIR_HD Index axisStride(int axis) const {
        return axis == 0 ? Index(1) : (axis == 1 ? Index(nx) : Index(nx) * Index(ny));
    }
};

WEIR_HD inline int bitCount3(int mask) {
    return (mask & 1) + ((mask >> 1) & 1) + ((mask >> 2) & 1);
}

// Bit a set where the edge from sample (x, y, z) along axis a is cut.
WEIR_HD inline int cutEdgesOfSample(const SampledFieldView& f, int x, int y, int z) {
    const Index i = f.sampleIndex(x, y, z);
    const bool in = f.inside(i);
    int mask = 0;
    if (x + 1 < f.nx && f.inside(i + 1) != in) {
        mask |= 1;
    }
    if (y + 1 < f.ny && f.inside(i + f.axisStride(1)) != in) {
        mask |= 2;
    }
    if (z + 1 < f.nz && f.inside(i + f.axisStride(2)) != in) {
        mask |= 4;
    }
    return mask;
}

// The field's gradient at a sample by central differences (one-sided on the lattice's faces),
// in field units per cell.
WEIR_HD inline Vec3f sampleGradient(const SampledFieldView& f, int x, int y, int z) {
    const int coords[3] = {x, y, z};
    const int dims[3] = {f.nx, f.ny, f.nz};
    const Index i = f.sampleIndex(x, y, z);
    float g[3];
    for (int a = 0; a < 3; ++a) {
        const Index stride = f.axisStride(a);
        const bool hasLow = coords[a] > 0, hasHigh = coords[a] + 1 < dims[a];
        const float high = hasHigh ? f.values[i + stride] : f.values[i];
        const float low = hasLow ? f.values[i - stride] : f.values[i];
        g[a] = (high - low) / float((hasLow ? 1 : 0) + (hasHigh ? 1 : 0));
    }
    return {g[0], g[1], g[2]};
}

// The vertex where the cut edge from sample (x, y, z) along `axis` crosses iso, by linear
// interpolation, and its unit normal from the interpolated gradient: out of the fluid, since
// the field grows outwards.
WEIR_HD inline void edgeVertex(const SampledFieldView& f, int x, int y, int z, int axis,
                               Vec3f& position, Vec3f& normal) {
    const Index i = f.sampleIndex(x, y, z);
    const Index j = i + f.axisStride(axis);
    const float a = f.values[i], b = f.values[j];
    const float t = (f.iso - a) / (b - a);  // in [0, 1]: a and b lie on different sides of iso
    int end[3] = {x, y, z};
    end[axis] += 1;
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
WEIR_HD inline int cubeCase(const SampledFieldView& f, int x, int y, int z) {
    int cubeCase = 0;
    for (int c = 0; c < 8; ++c) {
        const Index i = f.sampleIndex(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1));
        cubeCase |= f.inside(i) ? (1 << c) : 0;
    }
    return cubeCase;
}

// The marching-cubes table where the running backend can read it.
struct MarchingCubesTableView {
    const std::uint8_t* triangleCount;  // 256 entries
    const std::uint8_t* triangleEdges;  // 256 * 3 * kMaxTrianglesPerCube entries
};

// Vertex numbering: the cut edges of sample s get the vertices firstVertex(s), firstVertex(s) + 1,
// ... in axis order, where vertexEnd is the inclusive prefix sum of the samples' cut-edge counts.
WEIR_HD inline Index edgeVertexIndex(const SampledFieldView& f, const Index* vertexEnd, int x,
                                     int y, int z, int axis) {
    const int mask = cutEdgesOfSample(f, x, y, z);
    return vertexEnd[f.sampleIndex(x, y, z)] - bitCount3(mask) +
           bitCount3(mask & ((1 << axis) - 1));
}

// Writes the triangles of cell (x, y, z) as vertex indices, three per triangle, to out.
WEIR_HD inline void cellTriangles(const SampledFieldView& f, const MarchingCubesTableView& table,
                                  const Index* vertexEnd, int x, int y, int z, int cubeCaseBits,
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
