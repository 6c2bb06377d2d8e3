// The particle field table and its views over a HostParticles.
#include "io/field_registry.h"

namespace weir {

namespace {

struct FieldEntry {
    const char* name;
    std::vector<std::string> componentNames;
    std::vector<std::vector<Real> HostParticles::*> members;
    const char* unit;
    const char* colourName;  // a scalar's own name, a vector's magnitude's; "" not colourable
    FieldScale scale;
};

// The one place that lists the exported fields: add a row here and every writer picks it up,
// and the renderer can colour by it (`--color NAME`, the `c` key of weir view).
const std::vector<FieldEntry>& fieldTable() {
    using P = HostParticles;
    static const std::vector<FieldEntry> table = {
        {"velocity",
         {"vx", "vy", "vz"},
         {&P::vx, &P::vy, &P::vz},
         "m/s",
         "speed",
         FieldScale::ExpectedSpeed},
        {"density", {"density"}, {&P::rho}, "kg/m3", "density", FieldScale::RestDensity},
        {"pressure", {"pressure"}, {&P::p}, "Pa", "pressure", FieldScale::Hydrostatic},
    };
    return table;
}

template <class Array, class Particles>
std::vector<FieldDescT<Array>> fieldsOf(Particles& particles) {
    std::vector<FieldDescT<Array>> fields;
    for (const FieldEntry& entry : fieldTable()) {
        FieldDescT<Array> field{entry.name, int(entry.members.size()), entry.componentNames, {}};
        for (auto member : entry.members) {
            field.arrays.push_back(&(particles.*member));
        }
        fields.push_back(std::move(field));
    }
    return fields;
}

template <class Array, class Particles>
std::vector<Array*> columnsOf(Particles& particles) {
    std::vector<Array*> columns = {&particles.x, &particles.y, &particles.z};
    for (const auto& field : fieldsOf<Array>(particles)) {
        columns.insert(columns.end(), field.arrays.begin(), field.arrays.end());
    }
    return columns;
}

}  // namespace

const std::vector<FieldInfo>& particleFieldInfo() {
    static const std::vector<FieldInfo> info = [] {
        std::vector<FieldInfo> list;
        for (const FieldEntry& entry : fieldTable()) {
            list.push_back(
                {entry.name, int(entry.members.size()), entry.unit, entry.colourName, entry.scale});
        }
        return list;
    }();
    return info;
}

std::vector<FieldDesc> particleFields(const HostParticles& particles) {
    return fieldsOf<const std::vector<Real>>(particles);
}

std::vector<MutableFieldDesc> mutableParticleFields(HostParticles& particles) {
    return fieldsOf<std::vector<Real>>(particles);
}

std::vector<std::string> particleColumnNames() {
    std::vector<std::string> names = {"x", "y", "z"};
    for (const FieldEntry& entry : fieldTable()) {
        names.insert(names.end(), entry.componentNames.begin(), entry.componentNames.end());
    }
    return names;
}

std::vector<const std::vector<Real>*> particleColumns(const HostParticles& particles) {
    return columnsOf<const std::vector<Real>>(particles);
}

std::vector<std::vector<Real>*> mutableParticleColumns(HostParticles& particles) {
    return columnsOf<std::vector<Real>>(particles);
}

}  // namespace weir
