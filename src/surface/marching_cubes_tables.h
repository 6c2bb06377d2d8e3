// The marching-cubes case table (cube corner signs -> triangles on cube edges), generated at
// compile time from the cube's geometry instead of typed in, so that it is crack-free by
// construction: every face decides its own contour from its four corners alone, the same way for
// the two cubes that share it.
#pragma once

#include <array>
#include <cstdint>

#include "core/config.h"

namespace weir {

// Corner c of a cube sits at offset (c & 1, (c >> 1) & 1, (c >> 2) & 1) cells from the cube's
// lowest corner. Edge e = 4 * axis + k runs along `axis` from corner cubeEdgeStart(e) to
// cubeEdgeStart(e) | (1 << axis), where k holds the bits of the two other axes.
WEIR_HD constexpr int cubeEdgeAxis(int edge) { return edge / 4; }
WEIR_HD constexpr int cubeEdgeStart(int edge) {
    const int axis = edge / 4, k = edge % 4;
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    return ((k & 1) << b) | (((k >> 1) & 1) << c);
}

// The edge between two corners that differ in one bit.
constexpr int cubeEdgeBetween(int cornerA, int cornerB) {
    const int bit = cornerA ^ cornerB;
    const int axis = bit == 1 ? 0 : (bit == 2 ? 1 : 2);
    const int start = cornerA < cornerB ? cornerA : cornerB;
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    return 4 * axis + ((start >> b) & 1) + 2 * ((start >> c) & 1);
}

// Enough for any case: a case's loops hold at most 12 edge points, so at most 10 triangles.
constexpr int kMaxTrianglesPerCube = 10;

struct MarchingCubesTable {
    // triangleCount[cube case]; a case sets bit c where corner c is inside (field < iso).
    std::array<std::uint8_t, 256> triangleCount{};
    // Three cube edges per triangle, counter-clockwise seen from outside the fluid.
    std::array<std::array<std::uint8_t, 3 * kMaxTrianglesPerCube>, 256> triangleEdges{};
    bool complete = false;  // every loop of every case triangulated
};

// Whether two cube edges lie on a common face of the cube.
constexpr bool cubeEdgesShareFace(int edgeA, int edgeB) {
    for (int axis = 0; axis < 3; ++axis) {
        const int bit = 1 << axis;
        const int startA = cubeEdgeStart(edgeA), startB = cubeEdgeStart(edgeB);
        if (cubeEdgeAxis(edgeA) != axis && cubeEdgeAxis(edgeB) != axis &&
            (startA & bit) == (startB & bit)) {
            return true;
        }
    }
    return false;
}

// Triangulates the loop poly[0, k) (cube edges, in winding order) into table.triangleEdges
// with no diagonal between two points on one cube face: such a diagonal would lie in the face
// and could coincide with the neighbouring cube's, leaving an edge shared by four triangles. The
// triangle on edge (poly[0], poly[1]) is (poly[0], poly[1], poly[m]) for the first m that allows
// the rest to be triangulated likewise. False if there is no such triangulation.
constexpr bool triangulateLoop(const std::array<int, 12>& poly, int k, int cubeCase,
                               MarchingCubesTable& table, int& triangles) {
    for (int m = 2; m < k; ++m) {
        if ((m != 2 && cubeEdgesShareFace(poly[1], poly[m])) ||
            (m != k - 1 && cubeEdgesShareFace(poly[m], poly[0]))) {
            continue;
        }
        const int saved = triangles;
        auto& out = table.triangleEdges[cubeCase];
        out[3 * triangles + 0] = std::uint8_t(poly[0]);
        out[3 * triangles + 1] = std::uint8_t(poly[1]);
        out[3 * triangles + 2] = std::uint8_t(poly[m]);
        ++triangles;
        std::array<int, 12> before{}, after{};
        for (int i = 1; i <= m; ++i) {
            before[i - 1] = poly[i];
        }
        for (int i = m; i < k; ++i) {
            after[i - m] = poly[i];
        }
        after[k - m] = poly[0];
        if ((m == 2 || triangulateLoop(before, m, cubeCase, table, triangles)) &&
            (m == k - 1 || triangulateLoop(after, k - m + 1, cubeCase, table, triangles))) {
            return true;
        }
        triangles = saved;
    }
    return false;
}

// Builds one case. Each cube face is walked counter-clockwise as seen from outside the cube; an
// edge of the face that goes from an outside corner to an inside one "enters" and the next edge
// that leaves again "exits". The contour segment runs enter -> exit, which keeps the inside
// corners on its right seen from outside the cube; on a face with two diagonal inside corners it
// cuts each inside corner off on its own. Each cut cube edge enters on one of its two faces and
// exits on the other, so the segments chain into closed loops; each loop is triangulated with
// a winding that puts the triangles' normals on the outside (field > iso) side. Returns false if
// a loop could not be triangulated.
constexpr bool buildMarchingCubesCase(int cubeCase, MarchingCubesTable& table) {
    std::array<int, 12> next{};
    for (int& n : next) {
        n = -1;
    }
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            // In-plane axes (u, v) with u x v along the outward normal of this face.
            const int u = side == 1 ? (axis + 1) % 3 : (axis + 2) % 3;
            const int v = side == 1 ? (axis + 2) % 3 : (axis + 1) % 3;
            const int base = side << axis;
            const std::array<int, 4> corners = {base, base | (1 << u), base | (1 << u) | (1 << v),
                                                base | (1 << v)};
            std::array<bool, 4> inside{};
            for (int j = 0; j < 4; ++j) {
                inside[j] = ((cubeCase >> corners[j]) & 1) != 0;
            }
            for (int j = 0; j < 4; ++j) {
                if (inside[j] || !inside[(j + 1) % 4]) {
                    continue;  // not an entering face edge
                }
                for (int step = 1; step <= 4; ++step) {
                    const int k = (j + step) % 4;
                    if (inside[k] && !inside[(k + 1) % 4]) {
                        next[cubeEdgeBetween(corners[j], corners[(j + 1) % 4])] =
                            cubeEdgeBetween(corners[k], corners[(k + 1) % 4]);
                        break;
                    }
                }
            }
        }
    }
    int triangles = 0;
    bool complete = true;
    std::array<bool, 12> used{};
    for (int first = 0; first < 12; ++first) {
        if (next[first] < 0 || used[first]) {
            continue;
        }
        std::array<int, 12> loop{};
        int length = 0;
        for (int e = first; !used[e]; e = next[e]) {
            used[e] = true;
            loop[length++] = e;
        }
        complete = triangulateLoop(loop, length, cubeCase, table, triangles) && complete;
    }
    table.triangleCount[cubeCase] = std::uint8_t(triangles);
    return complete;
}

constexpr MarchingCubesTable buildMarchingCubesTable() {
    MarchingCubesTable table;
    table.complete = true;
    for (int cubeCase = 0; cubeCase < 256; ++cubeCase) {
        table.complete = buildMarchingCubesCase(cubeCase, table) && table.complete;
    }
    return table;
}

inline constexpr MarchingCubesTable kMarchingCubesTable = buildMarchingCubesTable();

// Facts every marching-cubes table has (Lorensen & Cline 1987): nothing in the empty and full
// cubes, one triangle for a lone corner, two for a cut across the cube.
static_assert(kMarchingCubesTable.complete);
static_assert(kMarchingCubesTable.triangleCount[0] == 0);
static_assert(kMarchingCubesTable.triangleCount[255] == 0);
static_assert(kMarchingCubesTable.triangleCount[1] == 1);
static_assert(kMarchingCubesTable.triangleCount[254] == 1);
static_assert(kMarchingCubesTable.triangleCount[0x0f] == 2);

}  // namespace weir
