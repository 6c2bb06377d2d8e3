// The per-particle fields that exporters write (besides positions), so writers loop over one list.
#pragma once

#include <string>
#include <vector>

#include "solver/particles.h"

namespace weir {

// One field: its name ("velocity"), component count, per-component names for column formats
// (PLY, CSV: "vx", "vy", "vz"; a scalar field's single component carries the field name), and
// the component arrays of one HostParticles. Array is `const std::vector<Real>` or, for
// readers filling particles, `std::vector<Real>`.
template <class Array>
struct FieldDescT {
    std::string name;
    int components = 0;
    std::vector<std::string> componentNames;
    std::vector<Array*> arrays;
};

using FieldDesc = FieldDescT<const std::vector<Real>>;
using MutableFieldDesc = FieldDescT<std::vector<Real>>;

// How a colour scale that stays put while a run goes is fixed for a field from the run's physics
// (render/colour_map.h): from 0 to the expected speed, around the rest density, from 0 to the
// hydrostatic pressure at the bottom of the deepest column, or (Data) from the values themselves.
enum class FieldScale { Data, ExpectedSpeed, RestDensity, Hydrostatic };

// What a field means beyond its arrays: its unit, and what the renderer colours it by, a scalar
// field by its own name and a vector field by its magnitude under `colourName` ("speed").
struct FieldInfo {
    std::string name;
    int components = 0;
    std::string unit;        // SI, ASCII: "m/s", "kg/m3", "Pa"
    std::string colourName;  // the colourable value's name; empty: not colourable
    FieldScale scale = FieldScale::Data;
};

// The registry's fields, in the order particleFields lists them.
const std::vector<FieldInfo>& particleFieldInfo();

// "velocity" (vx, vy, vz), "density" (rho), "pressure" (p), in the order writers emit them.
std::vector<FieldDesc> particleFields(const HostParticles& particles);
// The same list with writable arrays, for readers.
std::vector<MutableFieldDesc> mutableParticleFields(HostParticles& particles);

// Every format also writes each particle's id beside the fields: its index in the run's original
// order (frames keep particles in that order, so a frame's ids are 0 .. n - 1, the Python module's
// ids). An integer (int32: weir's particle counts stay below 2^31), not one of the Real fields.
// Readers that find ids put the particles back in id order (io/frame_reader.h).
inline constexpr const char* kParticleIdName = "id";

// Every scalar column in file order, for row formats (PLY, CSV): x, y, z, then each field's
// components. Names and arrays correspond index by index.
std::vector<std::string> particleColumnNames();
std::vector<const std::vector<Real>*> particleColumns(const HostParticles& particles);
std::vector<std::vector<Real>*> mutableParticleColumns(HostParticles& particles);

}  // namespace weir
