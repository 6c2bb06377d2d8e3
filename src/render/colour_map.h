// The particle field that sets the colour (speed, density, pressure), its value range, and the
// viridis colour map that turns values into colours.
#pragma once

#include <string>
#include <vector>

#include "solver/particles.h"

namespace weir {

struct Rgb {
    float r = 0, g = 0, b = 0;  // each in [0, 1]
};

// Viridis (perceptually uniform, readable in grey and by colour-blind viewers) at t in [0, 1],
// clamped, interpolated linearly between its eight published samples at i / 7.
Rgb viridis(double t);

enum class ColourField { Speed, Density, Pressure };

// "speed", "density" or "pressure"; anything else throws std::invalid_argument naming the value.
ColourField parseColourField(const std::string& name);
const char* colourFieldName(ColourField field);
const char* colourFieldUnit(ColourField field);  // "m/s", "kg/m3", "Pa"
ColourField nextColourField(ColourField field);

// The field's value for every particle, as float for the GPU.
std::vector<float> fieldValues(const HostParticles& particles, ColourField field);

struct ValueRange {
    double lo = 0, hi = 1;
    // t in [0, 1] for a value (clamped).
    double normalized(double value) const;
};

// The 1st to 99th percentile of the values (speed starts at 0), so that a few splashes do not
// wash out the map; widened to a non-empty range.
ValueRange robustRange(const std::vector<float>& values, ColourField field);
// The union of two ranges.
ValueRange unite(const ValueRange& a, const ValueRange& b);
// A range from the physics of a run, for colours that stay put while it runs: speed up to the
// expected speed, density around rest density, pressure up to the hydrostatic pressure at the
// bottom of the deepest column.
ValueRange physicalRange(ColourField field, double restDensity, double expectedSpeed,
                         double hydrostaticPressure);

}  // namespace weir
