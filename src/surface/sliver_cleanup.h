// Sliver cleanup of a marching-cubes mesh: short edges collapsed and flat triangles' long edges
// flipped, keeping the mesh closed and consistently wound.
#pragma once

#include <cstddef>

#include "surface/triangle_mesh.h"

namespace weir {

// The goal: no edge under this fraction of a marching-cubes cell, no angle under this many
// degrees.
constexpr double kSliverEdgeFraction = 0.01;
constexpr double kSliverAngleDegrees = 1.0;

struct SliverCleanupReport {
    std::size_t badTriangles = 0;  // found before the cleanup
    std::size_t collapses = 0;     // edges collapsed
    std::size_t flips = 0;         // edges flipped
    std::size_t specks = 0;        // closed pieces under a tenth of a cell across, removed
    std::size_t left = 0;          // bad triangles no safe operation could fix
};

// Marching cubes puts a vertex near a lattice sample whenever the field there is near the
// iso-value, and the triangles around it become needles (an edge far shorter than the others) or
// caps (an angle near 180 degrees). Each bad triangle is fixed locally: a needle's shortest edge
// is collapsed to its midpoint, a cap's longest edge is flipped (else its shortest edge
// collapsed). An operation is done only where it keeps the mesh a closed 2-manifold (the edge has
// two triangles; a collapse meets the link condition and leaves every vertex three neighbours or
// more; a flip does not make an edge that exists) and turns no triangle over. A bad triangle left
// after that lies on a speck, a closed piece of a few triangles under a tenth of a cell across
// (spray a hair past the iso-value, where every collapse would pinch): the speck is removed.
// The cleaner knows the triangles of the vertices within three rings of the bad triangles only
// (found by parallel passes over the mesh) and leaves any operation that would reach further to
// a next round with rings around what is left, so that it costs what it fixes, not the mesh.
// Dead triangles and unused vertices are dropped at the end, each hole taking the last triangle
// (vertex) still used. Triangles are checked in parallel; a mesh without slivers is left as it is.
SliverCleanupReport removeSlivers(TriangleMesh& mesh, double cellSize);

}  // namespace weir
