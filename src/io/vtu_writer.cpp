// writeVtu: XML header with DataArray offsets, then the appended raw blocks.
#include "io/vtu_writer.h"

#include <bit>
#include <cstdint>
#include <functional>
#include <ostream>
#include <type_traits>
#include <vector>

#include "io/atomic_file.h"
#include "io/field_registry.h"
#include "io/io_util.h"

namespace weir {

static_assert(std::endian::native == std::endian::little, "VTU/PLY writers emit native bytes");

namespace {

template <class T>
constexpr const char* vtkType() {
    if constexpr (std::is_same_v<T, float>) {
        return "Float32";
    } else if constexpr (std::is_same_v<T, double>) {
        return "Float64";
    } else if constexpr (std::is_same_v<T, std::int32_t>) {
        return "Int32";
    } else {
        static_assert(std::is_same_v<T, std::uint8_t>);
        return "UInt8";
    }
}

// One DataArray of the appended section: its header attributes and how to write its bytes.
struct AppendedArray {
    std::string name;
    const char* type;
    int components;
    std::uint64_t bytes;
    std::function<void(std::ostream&)> writeData;
};

template <class T>
AppendedArray realArray(std::string name, std::vector<const std::vector<Real>*> arrays,
                        std::size_t n) {
    const int components = int(arrays.size());
    return {std::move(name), vtkType<T>(), components, n * components * sizeof(T),
            [arrays, n](std::ostream& out) { writeInterleaved<T>(out, arrays, n); }};
}

template <class T, class ValueAt>
AppendedArray generatedArray(std::string name, std::size_t n, ValueAt valueAt) {
    return {std::move(name), vtkType<T>(), 1, n * sizeof(T),
            [n, valueAt](std::ostream& out) { writeSequence<T>(out, n, valueAt); }};
}

void writeDataArrayTag(std::ostream& out, const char* indent, const AppendedArray& array,
                       std::uint64_t offset, const char* extraAttribute = "") {
    out << indent << "<DataArray type=\"" << array.type << "\" Name=\"" << array.name << '"';
    if (array.components != 1) {
        out << " NumberOfComponents=\"" << array.components << '"';
    }
    out << extraAttribute << " format=\"appended\" offset=\"" << offset << "\"/>\n";
}

}  // namespace

void writeVtu(const std::string& path, const HostParticles& particles, double time) {
    const std::size_t n = particles.size();
    const AppendedArray timeValue =
        generatedArray<double>("TimeValue", 1, [time](std::size_t) { return time; });
    std::vector<AppendedArray> pointData;
    for (const FieldDesc& field : particleFields(particles)) {
        pointData.push_back(realArray<Real>(field.name, field.arrays, n));
    }
    pointData.push_back(generatedArray<std::int32_t>(
        kParticleIdName, n, [&particles](std::size_t i) { return particles.idOf(i); }));
    const AppendedArray points =
        realArray<Real>("Points", {&particles.x, &particles.y, &particles.z}, n);
    // One VTK_VERTEX (type 1) cell per particle: connectivity i, end offset i + 1.
    const std::vector<AppendedArray> cells = {
        generatedArray<std::int32_t>("connectivity", n, [](std::size_t i) { return i; }),
        generatedArray<std::int32_t>("offsets", n, [](std::size_t i) { return i + 1; }),
        generatedArray<std::uint8_t>("types", n, [](std::size_t) { return 1; }),
    };

    writeFileAtomically(path, [&](std::ostream& out) {
        std::uint64_t offset = 0;
        std::vector<const AppendedArray*> order;
        const auto tag = [&](const char* indent, const AppendedArray& array,
                             const char* extraAttribute = "") {
            writeDataArrayTag(out, indent, array, offset, extraAttribute);
            offset += sizeof(std::uint64_t) + array.bytes;
            order.push_back(&array);
        };
        out << "<?xml version=\"1.0\"?>\n"
               "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\""
               " header_type=\"UInt64\">\n"
               "  <UnstructuredGrid>\n"
               "    <FieldData>\n";
        tag("      ", timeValue, " NumberOfTuples=\"1\"");
        out << "    </FieldData>\n"
            << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n"
            << "      <PointData>\n";
        for (const AppendedArray& array : pointData) {
            tag("        ", array);
        }
        out << "      </PointData>\n"
               "      <Points>\n";
        tag("        ", points);
        out << "      </Points>\n"
               "      <Cells>\n";
        for (const AppendedArray& array : cells) {
            tag("        ", array);
        }
        out << "      </Cells>\n"
               "    </Piece>\n"
               "  </UnstructuredGrid>\n"
               "  <AppendedData encoding=\"raw\">\n"
               "   _";
        for (const AppendedArray* array : order) {
            out.write(reinterpret_cast<const char*>(&array->bytes), sizeof(array->bytes));
            array->writeData(out);
        }
        out << "\n  </AppendedData>\n"
               "</VTKFile>\n";
    });
}

}  // namespace weir
