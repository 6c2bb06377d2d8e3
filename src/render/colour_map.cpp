// Viridis, field values and value ranges.
#include "render/colour_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace weir {

namespace {

// Viridis sampled at i / 7 (matplotlib's published colours #440154 ... #fde725).
constexpr unsigned kViridis[8] = {0x440154, 0x46327e, 0x365c8d, 0x277f8e,
                                  0x1fa187, 0x4ac16d, 0xa0da39, 0xfde725};

Rgb fromHex(unsigned hex) {
    return {float((hex >> 16) & 0xff) / 255.0f, float((hex >> 8) & 0xff) / 255.0f,
            float(hex & 0xff) / 255.0f};
}

// The q-quantile (q in [0, 1]) of values, reordering a copy.
double quantile(std::vector<float> values, double q) {
    const std::size_t k = std::size_t(q * double(values.size() - 1) + 0.5);
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
    return values[k];
}

}  // namespace

Rgb viridis(double t) {
    if (!(t > 0)) {
        t = 0;  // also NaN
    }
    const double x = std::min(t, 1.0) * 7;
    const int i = std::min(int(x), 6);
    const float f = float(x - i);
    const Rgb a = fromHex(kViridis[i]);
    const Rgb b = fromHex(kViridis[i + 1]);
    return {a.r + (b.r - a.r) * f, a.g + (b.g - a.g) * f, a.b + (b.b - a.b) * f};
}

ColourField parseColourField(const std::string& name) {
    if (name == "speed") {
        return ColourField::Speed;
    }
    if (name == "density") {
        return ColourField::Density;
    }
    if (name == "pressure") {
        return ColourField::Pressure;
    }
    throw std::invalid_argument("colour field '" + name +
                                "' is not known; allowed: speed, density, pressure");
}

const char* colourFieldName(ColourField field) {
    switch (field) {
        case ColourField::Speed:
            return "speed";
        case ColourField::Density:
            return "density";
        case ColourField::Pressure:
            return "pressure";
    }
    return "?";
}

const char* colourFieldUnit(ColourField field) {
    switch (field) {
        case ColourField::Speed:
            return "m/s";
        case ColourField::Density:
            return "kg/m3";
        case ColourField::Pressure:
            return "Pa";
    }
    return "";
}

ColourField nextColourField(ColourField field) {
    switch (field) {
        case ColourField::Speed:
            return ColourField::Density;
        case ColourField::Density:
            return ColourField::Pressure;
        case ColourField::Pressure:
            return ColourField::Speed;
    }
    return ColourField::Speed;
}

std::vector<float> fieldValues(const HostParticles& particles, ColourField field) {
    const std::size_t n = particles.size();
    std::vector<float> values(n);
    for (std::size_t i = 0; i < n; ++i) {
        switch (field) {
            case ColourField::Speed: {
                const double vx = particles.vx[i], vy = particles.vy[i], vz = particles.vz[i];
                values[i] = float(std::sqrt(vx * vx + vy * vy + vz * vz));
                break;
            }
            case ColourField::Density:
                values[i] = float(particles.rho[i]);
                break;
            case ColourField::Pressure:
                values[i] = float(particles.p[i]);
                break;
        }
    }
    return values;
}

double ValueRange::normalized(double value) const {
    return std::clamp((value - lo) / (hi - lo), 0.0, 1.0);
}

ValueRange robustRange(const std::vector<float>& values, ColourField field) {
    ValueRange range{0, 0};
    if (!values.empty()) {
        range.lo = field == ColourField::Speed ? 0.0 : quantile(values, 0.01);
        range.hi = quantile(values, 0.99);
    }
    if (!(range.hi > range.lo)) {
        const double pad = std::max(std::abs(range.lo) * 0.01, 1e-6);
        range.hi = range.lo + pad;
        if (field != ColourField::Speed) {
            range.lo -= pad;
        }
    }
    return range;
}

ValueRange unite(const ValueRange& a, const ValueRange& b) {
    return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}

ValueRange physicalRange(ColourField field, double restDensity, double expectedSpeed,
                         double hydrostaticPressure) {
    switch (field) {
        case ColourField::Speed:
            return {0, std::max(expectedSpeed, 1e-6)};
        case ColourField::Density:
            return {0.9 * restDensity, 1.05 * restDensity};
        case ColourField::Pressure:
            return {0, std::max(hydrostaticPressure, 1e-6)};
    }
    return {};
}

}  // namespace weir
