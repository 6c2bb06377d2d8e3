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

namespace {

struct ColourEntry {
    std::string name, unit;
    FieldScale scale;
    std::size_t field;
    bool magnitude;
};

const std::vector<ColourEntry>& colourTable() {
    static const std::vector<ColourEntry> table = [] {
        std::vector<ColourEntry> list;
        const std::vector<FieldInfo>& fields = particleFieldInfo();
        for (std::size_t i = 0; i < fields.size(); ++i) {
            if (!fields[i].colourName.empty()) {
                list.push_back({fields[i].colourName, fields[i].unit, fields[i].scale, i,
                                fields[i].components > 1});
            }
        }
        return list;
    }();
    return table;
}

}  // namespace

const ColourField ColourField::Speed = parseColourField("speed");
const ColourField ColourField::Density = parseColourField("density");
const ColourField ColourField::Pressure = parseColourField("pressure");

const std::vector<ColourField>& ColourField::all() {
    static const std::vector<ColourField> fields = [] {
        std::vector<ColourField> list;
        for (std::size_t i = 0; i < colourTable().size(); ++i) {
            list.push_back(ColourField(i));
        }
        return list;
    }();
    return fields;
}

const std::string& ColourField::name() const { return colourTable()[index_].name; }
const std::string& ColourField::unit() const { return colourTable()[index_].unit; }
FieldScale ColourField::scale() const { return colourTable()[index_].scale; }
std::size_t ColourField::fieldIndex() const { return colourTable()[index_].field; }
bool ColourField::magnitude() const { return colourTable()[index_].magnitude; }

ColourField parseColourField(const std::string& name) {
    for (std::size_t i = 0; i < colourTable().size(); ++i) {
        if (colourTable()[i].name == name) {
            return ColourField::all()[i];
        }
    }
    throw std::invalid_argument("colour field '" + name +
                                "' is not known; allowed: " + colourFieldList());
}

const char* colourFieldName(ColourField field) { return field.name().c_str(); }

const char* colourFieldUnit(ColourField field) { return field.unit().c_str(); }

ColourField nextColourField(ColourField field) {
    const std::vector<ColourField>& all = ColourField::all();
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (all[i] == field) {
            return all[(i + 1) % all.size()];
        }
    }
    return all.front();
}

std::vector<std::string> colourFieldNames() {
    std::vector<std::string> names;
    for (const ColourEntry& entry : colourTable()) {
        names.push_back(entry.name);
    }
    return names;
}

std::string colourFieldList() {
    std::string list;
    for (const ColourEntry& entry : colourTable()) {
        list += (list.empty() ? "" : ", ") + entry.name;
    }
    return list;
}

std::vector<float> fieldValues(const HostParticles& particles, ColourField field) {
    const std::size_t n = particles.size();
    const FieldDesc desc = particleFields(particles)[field.fieldIndex()];
    std::vector<float> values(n);
    if (!field.magnitude()) {
        const std::vector<Real>& a = *desc.arrays[0];
        for (std::size_t i = 0; i < n; ++i) {
            values[i] = float(a[i]);
        }
        return values;
    }
    for (std::size_t i = 0; i < n; ++i) {
        double sum = 0;
        for (const std::vector<Real>* a : desc.arrays) {
            sum += double((*a)[i]) * double((*a)[i]);
        }
        values[i] = float(std::sqrt(sum));
    }
    return values;
}

double ValueRange::normalized(double value) const {
    return std::clamp((value - lo) / (hi - lo), 0.0, 1.0);
}

ValueRange robustRange(const std::vector<float>& values, ColourField field) {
    ValueRange range{0, 0};
    if (!values.empty()) {
        range.lo = field.magnitude() ? 0.0 : quantile(values, 0.01);
        range.hi = quantile(values, 0.99);
    }
    if (!(range.hi > range.lo)) {
        const double pad = std::max(std::abs(range.lo) * 0.01, 1e-6);
        range.hi = range.lo + pad;
        if (!field.magnitude()) {
            range.lo -= pad;
        }
    }
    return range;
}

ValueRange unite(const ValueRange& a, const ValueRange& b) {
    return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}

ValueRange physicalRange(ColourField field, double restDensity, double expectedSpeed,
                         double hydrostaticPressure, ValueRange data) {
    switch (field.scale()) {
        case FieldScale::ExpectedSpeed:
            return {0, std::max(expectedSpeed, 1e-6)};
        case FieldScale::RestDensity:
            return {0.9 * restDensity, 1.05 * restDensity};
        case FieldScale::Hydrostatic:
            return {0, std::max(hydrostaticPressure, 1e-6)};
        case FieldScale::Data:
            break;
    }
    return data;
}

}  // namespace weir
