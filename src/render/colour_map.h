// The particle value that sets the colour (any field of the registry: speed, density, pressure),
// its value range, and the viridis colour map that turns values into colours.
#pragma once

#include <string>
#include <vector>

#include "io/field_registry.h"
#include "solver/particles.h"

namespace weir {

struct Rgb {
    float r = 0, g = 0, b = 0;  // each in [0, 1]
};

// Viridis (perceptually uniform, readable in grey and by colour-blind viewers) at t in [0, 1],
// clamped, interpolated linearly between its eight published samples at i / 7.
Rgb viridis(double t);

// A value particles can be coloured by, derived from the field registry (io/field_registry.h):
// each scalar field by its name ("density", "pressure") and each vector field by its magnitude
// ("speed" for velocity), so a field added to the registry is colourable with no change here.
class ColourField {
   public:
    // Handles for the fields that code names; all() lists every one.
    static const ColourField Speed, Density, Pressure;
    // In the registry's order.
    static const std::vector<ColourField>& all();

    const std::string& name() const;
    const std::string& unit() const;
    FieldScale scale() const;
    std::size_t fieldIndex() const;  // in particleFields()
    bool magnitude() const;          // a vector field's length
    friend bool operator==(ColourField a, ColourField b) { return a.index_ == b.index_; }

   private:
    explicit ColourField(std::size_t index) : index_(index) {}
    std::size_t index_;  // in all()
};

// A colour field's name; anything else throws std::invalid_argument naming the value and the
// allowed names.
ColourField parseColourField(const std::string& name);
const char* colourFieldName(ColourField field);
const char* colourFieldUnit(ColourField field);  // "m/s", "kg/m3", "Pa"
// The next one in all(), wrapping round (the `c` key of weir view).
ColourField nextColourField(ColourField field);
// Every colour field's name, and as "speed, density, pressure".
std::vector<std::string> colourFieldNames();
std::string colourFieldList();

// The field's value for every particle, as float for the GPU.
std::vector<float> fieldValues(const HostParticles& particles, ColourField field);

struct ValueRange {
    double lo = 0, hi = 1;
    // t in [0, 1] for a value (clamped).
    double normalized(double value) const;
};

// The 1st to 99th percentile of the values (a magnitude starts at 0), so that a few splashes do not
// wash out the map; widened to a non-empty range.
ValueRange robustRange(const std::vector<float>& values, ColourField field);
// The union of two ranges.
ValueRange unite(const ValueRange& a, const ValueRange& b);
// A range from the physics of a run, for colours that stay put while it runs, by the field's
// FieldScale: speed up to the expected speed, density around rest density, pressure up to the
// hydrostatic pressure at the bottom of the deepest column; a field of scale Data gets `data`.
ValueRange physicalRange(ColourField field, double restDensity, double expectedSpeed,
                         double hydrostaticPressure, ValueRange data = {});

}  // namespace weir
