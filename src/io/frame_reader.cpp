// Frame readers: a minimal VTU header parser with appended-block bounds checks, PLY, CSV.
#include "io/frame_reader.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <string_view>
#include <vector>

#include "io/field_registry.h"
#include "io/io_error.h"
#include "io/io_util.h"

namespace weir {

static_assert(std::endian::native == std::endian::little, "the readers expect native bytes");

namespace {

[[noreturn]] void malformed(const std::string& path, const std::string& what) {
    throw IoError("cannot read '" + path + "': " + what);
}

template <class T>
T loadValue(const char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
}

// Copies count values of type From starting at bytes, converted to To, to
// arrays[0][0], arrays[1][0], ..., arrays[0][1], ... (the inverse of writeInterleaved).
template <class From, class To>
void deinterleave(const char* bytes, const std::vector<std::vector<To>*>& arrays,
                  std::size_t count) {
    const std::size_t k = arrays.size();
    for (auto* array : arrays) {
        array->resize(count / k);
    }
    for (std::size_t i = 0; i < count; ++i) {
        (*arrays[i % k])[i / k] = To(loadValue<From>(bytes + i * sizeof(From)));
    }
}

using Attributes = std::map<std::string, std::string>;

// The name="value" pairs of a tag body (no entities: enough for the headers writeVtu writes).
Attributes attributesOf(std::string_view body) {
    Attributes attributes;
    for (std::size_t equals; (equals = body.find("=\"")) != std::string_view::npos;) {
        const std::size_t nameStart = body.find_last_of(" \t\r\n", equals) + 1;  // npos + 1 == 0
        const std::size_t valueEnd = body.find('"', equals + 2);
        if (valueEnd == std::string_view::npos) {
            break;
        }
        attributes[std::string(body.substr(nameStart, equals - nameStart))] =
            body.substr(equals + 2, valueEnd - equals - 2);
        body.remove_prefix(valueEnd + 1);
    }
    return attributes;
}

// The attributes of every <element ...> tag in xml, in order.
std::vector<Attributes> tagsNamed(std::string_view xml, const std::string& element) {
    std::vector<Attributes> tags;
    const std::string open = "<" + element;
    for (std::size_t at = xml.find(open); at != std::string_view::npos;
         at = xml.find(open, at + 1)) {
        const std::size_t bodyStart = at + open.size();
        const std::size_t end = xml.find('>', bodyStart);
        if (end == std::string_view::npos) {
            break;
        }
        if (xml.find_first_of(" \t\r\n/>", bodyStart) == bodyStart) {  // not a longer name
            tags.push_back(attributesOf(xml.substr(bodyStart, end - bodyStart)));
        }
    }
    return tags;
}

// A .vtu as written by writeVtu: the XML header's arrays and the appended raw blocks, every
// block's bounds checked on opening.
class VtuFile {
   public:
    explicit VtuFile(const std::string& path) : path_(path), bytes_(readFileBytes(path)) {
        const std::string appendedTag = "<AppendedData encoding=\"raw\">";
        const std::size_t appendedPos = bytes_.find(appendedTag);
        if (appendedPos == std::string::npos) {
            fail("no " + appendedTag + " section (not a VTU file from weir, or truncated)");
        }
        const std::string_view header = std::string_view(bytes_).substr(0, appendedPos);
        const auto files = tagsNamed(header, "VTKFile");
        if (files.empty()) {
            fail("no <VTKFile> element");
        }
        expectAttribute(files[0], "type", "UnstructuredGrid");
        expectAttribute(files[0], "byte_order", "LittleEndian");
        expectAttribute(files[0], "header_type", "UInt64");
        auto pieces = tagsNamed(header, "Piece");
        if (pieces.size() != 1 || !parseNumber(pieces[0]["NumberOfPoints"], numberOfPoints_)) {
            fail("expected one <Piece> with a NumberOfPoints");
        }
        // Every point takes at least 12 bytes (its position as Float32): a count past what the
        // file can hold is refused before anything is allocated (or a byte count overflows).
        if (numberOfPoints_ > bytes_.size() / 12) {
            fail("NumberOfPoints=\"" + std::to_string(numberOfPoints_) + "\" is more than the " +
                 std::to_string(bytes_.size()) + " bytes of the file can hold");
        }
        for (Attributes& dataArray : tagsNamed(header, "DataArray")) {
            parseDataArray(dataArray);
        }

        std::size_t marker = bytes_.find_first_not_of(" \t\r\n", appendedPos + appendedTag.size());
        if (marker == std::string::npos || bytes_[marker] != '_') {
            fail("no '_' marker at the start of the appended data (truncated?)");
        }
        appendedStart_ = marker + 1;
        std::size_t end = appendedStart_;
        for (auto& [name, array] : arrays_) {
            end = std::max(end, checkBlock(name, array));
        }
        if (bytes_.find("</VTKFile>", end) == std::string::npos) {
            fail("truncated: no </VTKFile> after the appended data");
        }
    }

    std::size_t numberOfPoints() const { return numberOfPoints_; }

    double time() const {
        std::vector<double> value;
        read<double>("TimeValue", {&value}, 1);
        return value[0];
    }

    // Reads array `name` of `tuples` tuples into arrays (one per component), converting the
    // file's Float32 or Float64 values to T.
    template <class T>
    void read(const std::string& name, const std::vector<std::vector<T>*>& arrays,
              std::size_t tuples) const {
        const auto found = arrays_.find(name);
        if (found == arrays_.end()) {
            fail("no DataArray '" + name + "'");
        }
        const Array& array = found->second;
        if (array.components != arrays.size()) {
            fail("DataArray '" + name + "' has " + std::to_string(array.components) +
                 " components, expected " + std::to_string(arrays.size()));
        }
        const std::size_t valueSize = array.type == "Float32" ? 4 : array.type == "Float64" ? 8 : 0;
        if (valueSize == 0) {
            fail("DataArray '" + name + "' has type " + array.type +
                 ", expected Float32 or Float64");
        }
        const std::size_t count = tuples * arrays.size();
        if (array.bytes != count * valueSize) {
            fail("DataArray '" + name + "' holds " + std::to_string(array.bytes) +
                 " bytes, expected " + std::to_string(count * valueSize) + " for " +
                 std::to_string(tuples) + " tuples of " + array.type);
        }
        const char* data = bytes_.data() + appendedStart_ + array.offset + sizeof(std::uint64_t);
        if (valueSize == 4) {
            deinterleave<float>(data, arrays, count);
        } else {
            deinterleave<double>(data, arrays, count);
        }
    }

    bool has(const std::string& name) const { return arrays_.count(name) != 0; }

    // Reads the integer array `name` (Int32 or Int64, one component) of `tuples` values.
    std::vector<std::int64_t> readIntegers(const std::string& name, std::size_t tuples) const {
        const Array& array = arrays_.at(name);
        const std::size_t valueSize = array.type == "Int32" ? 4 : array.type == "Int64" ? 8 : 0;
        if (valueSize == 0 || array.components != 1) {
            fail("DataArray '" + name + "' has type " + array.type + " with " +
                 std::to_string(array.components) +
                 " components, expected one component of Int32 or Int64");
        }
        if (array.bytes != tuples * valueSize) {
            fail("DataArray '" + name + "' holds " + std::to_string(array.bytes) +
                 " bytes, expected " + std::to_string(tuples * valueSize) + " for " +
                 std::to_string(tuples) + " values of " + array.type);
        }
        const char* data = bytes_.data() + appendedStart_ + array.offset + sizeof(std::uint64_t);
        std::vector<std::int64_t> values(tuples);
        for (std::size_t i = 0; i < tuples; ++i) {
            values[i] = valueSize == 4 ? loadValue<std::int32_t>(data + 4 * i)
                                       : loadValue<std::int64_t>(data + 8 * i);
        }
        return values;
    }

   private:
    struct Array {
        std::string type;
        std::size_t components = 1;
        std::uint64_t offset = 0;
        std::uint64_t bytes = 0;  // from the block's UInt64 header
    };

    [[noreturn]] void fail(const std::string& what) const { malformed(path_, what); }

    void expectAttribute(const Attributes& attributes, const std::string& name,
                         const std::string& expected) const {
        const auto found = attributes.find(name);
        const std::string actual =
            found == attributes.end() ? "missing" : '"' + found->second + '"';
        if (actual != '"' + expected + '"') {
            fail("VTKFile " + name + " is " + actual + ", expected \"" + expected + '"');
        }
    }

    void parseDataArray(Attributes& attributes) {
        const std::string& name = attributes["Name"];
        Array array{attributes["type"], 1, 0, 0};
        if (attributes["format"] != "appended") {
            fail("DataArray '" + name + "' has format \"" + attributes["format"] +
                 "\", expected \"appended\"");
        }
        if (!parseNumber(attributes["offset"], array.offset) ||
            (attributes.count("NumberOfComponents") &&
             !parseNumber(attributes["NumberOfComponents"], array.components)) ||
            array.components == 0 || array.components > 16) {
            fail("DataArray '" + name +
                 "' has a bad offset or NumberOfComponents (allowed: " + "1..16)");
        }
        arrays_[name] = array;
    }

    // Checks that the block at array.offset (UInt64 byte count, then the bytes) lies inside the
    // file, records its byte count and returns where it ends.
    std::size_t checkBlock(const std::string& name, Array& array) const {
        const std::size_t available = bytes_.size() - appendedStart_;
        if (array.offset > available || available - array.offset < sizeof(std::uint64_t)) {
            fail("truncated: DataArray '" + name + "' starts at appended offset " +
                 std::to_string(array.offset) + " but the appended data has only " +
                 std::to_string(available) + " bytes");
        }
        std::memcpy(&array.bytes, bytes_.data() + appendedStart_ + array.offset,
                    sizeof(std::uint64_t));
        const std::size_t left = available - array.offset - sizeof(std::uint64_t);
        if (array.bytes > left) {
            fail("truncated: DataArray '" + name + "' needs " + std::to_string(array.bytes) +
                 " bytes but only " + std::to_string(left) + " follow its header");
        }
        return appendedStart_ + array.offset + sizeof(std::uint64_t) + array.bytes;
    }

    std::string path_;
    std::string bytes_;
    std::size_t numberOfPoints_ = 0;
    std::size_t appendedStart_ = 0;
    std::map<std::string, Array> arrays_;
};

// The PLY property types (binary): each name and its alias (int32, float64, ...).
struct PlyType {
    const char* name;
    const char* alias;
    std::size_t size;
    bool isFloat;
    bool isSigned;
};

constexpr PlyType kPlyTypes[] = {
    {"char", "int8", 1, false, true},    {"uchar", "uint8", 1, false, false},
    {"short", "int16", 2, false, true},  {"ushort", "uint16", 2, false, false},
    {"int", "int32", 4, false, true},    {"uint", "uint32", 4, false, false},
    {"float", "float32", 4, true, true}, {"double", "float64", 8, true, true},
};

const PlyType* plyTypeNamed(const std::string& name) {
    for (const PlyType& type : kPlyTypes) {
        if (name == type.name || name == type.alias) {
            return &type;
        }
    }
    return nullptr;
}

std::string plyTypeList() {
    std::string list;
    for (const PlyType& type : kPlyTypes) {
        list += (list.empty() ? "" : ", ") + std::string(type.name);
    }
    return list;
}

// One value of a PLY property, converted to T.
template <class T>
T loadPlyValue(const char* at, const PlyType& type) {
    if (type.isFloat) {
        return type.size == 4 ? T(loadValue<float>(at)) : T(loadValue<double>(at));
    }
    switch (type.size) {
        case 1:
            return type.isSigned ? T(loadValue<std::int8_t>(at)) : T(loadValue<std::uint8_t>(at));
        case 2:
            return type.isSigned ? T(loadValue<std::int16_t>(at)) : T(loadValue<std::uint16_t>(at));
        default:
            return type.isSigned ? T(loadValue<std::int32_t>(at)) : T(loadValue<std::uint32_t>(at));
    }
}

std::string_view withoutCarriageReturn(std::string_view line) {
    return line.ends_with('\r') ? line.substr(0, line.size() - 1) : line;
}

// Splits text at `separator`; the last piece runs to the end.
std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> pieces;
    for (std::size_t start = 0;;) {
        const std::size_t end = text.find(separator, start);
        pieces.push_back(text.substr(start, end - start));
        if (end == std::string_view::npos) {
            return pieces;
        }
        start = end + 1;
    }
}

}  // namespace

HostParticles readVtu(const std::string& path, double* time) {
    const VtuFile file(path);
    const std::size_t n = file.numberOfPoints();
    HostParticles particles;
    file.read<Real>("Points", {&particles.x, &particles.y, &particles.z}, n);
    for (const MutableFieldDesc& field : mutableParticleFields(particles)) {
        file.read(field.name, field.arrays, n);
    }
    if (file.has(kParticleIdName)) {
        orderParticlesById(particles, file.readIntegers(kParticleIdName, n), path);
    }
    if (time != nullptr) {
        *time = file.time();
    }
    return particles;
}

double readVtuTime(const std::string& path) { return VtuFile(path).time(); }

HostParticles readPly(const std::string& path) {
    const std::string bytes = readFileBytes(path);
    const auto fail = [&](const std::string& what) { malformed(path, what); };
    const std::size_t endHeader = bytes.find("\nend_header");
    const std::size_t bodyStart = bytes.find('\n', endHeader + 1);
    if (endHeader == std::string::npos || bodyStart == std::string::npos) {
        fail("no end_header line (not a PLY file, or truncated)");
    }

    struct Property {
        std::size_t offset;  // within a vertex row
        PlyType type;
    };
    std::map<std::string, Property> properties;
    std::size_t rowBytes = 0;
    std::size_t vertexCount = 0;
    bool sawFormat = false;
    bool sawVertex = false;
    std::istringstream header(bytes.substr(0, endHeader));
    std::string line;
    for (int lineNumber = 1; std::getline(header, line); ++lineNumber) {
        if (!line.empty() && line.back() == '\r') {
            line.pop_back();
        }
        std::istringstream words(line);
        std::string keyword, type, name;
        words >> keyword;
        const std::string where = "header line " + std::to_string(lineNumber) + " '" + line + "'";
        if (lineNumber == 1 && keyword != "ply") {
            fail("does not start with 'ply' (not a PLY file)");
        } else if (keyword == "format") {
            if (line != "format binary_little_endian 1.0") {
                fail(where + ": expected 'format binary_little_endian 1.0'");
            }
            sawFormat = true;
        } else if (keyword == "element") {
            words >> name;
            if (name != "vertex" || sawVertex || !(words >> vertexCount)) {
                fail(where + ": expected a single 'element vertex <count>'");
            }
            sawVertex = true;
        } else if (keyword == "property") {
            words >> type >> name;
            const PlyType* plyType = plyTypeNamed(type);
            if (!sawVertex || plyType == nullptr) {
                fail(where + ": expected a vertex property of a numeric type (" + plyTypeList() +
                     ")");
            }
            properties[name] = {rowBytes, *plyType};
            rowBytes += plyType->size;
        }
    }

    if (!sawFormat || !sawVertex) {
        fail("the header has no 'format' or no 'element vertex' line");
    }
    HostParticles particles;
    const std::size_t bodyBytes = bytes.size() - (bodyStart + 1);
    if (rowBytes == 0 || bodyBytes / rowBytes != vertexCount || bodyBytes % rowBytes != 0) {
        fail("truncated or oversized: " + std::to_string(vertexCount) + " vertices of " +
             std::to_string(rowBytes) + " bytes need " + std::to_string(vertexCount * rowBytes) +
             " bytes after the header, the file has " + std::to_string(bodyBytes));
    }
    const auto names = particleColumnNames();
    const auto columns = mutableParticleColumns(particles);
    for (std::size_t c = 0; c < names.size(); ++c) {
        const auto found = properties.find(names[c]);
        if (found == properties.end()) {
            fail("no vertex property '" + names[c] + "'");
        }
        const Property property = found->second;
        columns[c]->resize(vertexCount);
        for (std::size_t i = 0; i < vertexCount; ++i) {
            const char* at = bytes.data() + bodyStart + 1 + i * rowBytes + property.offset;
            (*columns[c])[i] = property.type.isFloat && property.type.size == 4
                                   ? loadValue<float>(at)  // exact in a float build
                                   : Real(loadPlyValue<double>(at, property.type));
        }
    }
    const auto id = properties.find(kParticleIdName);
    if (id != properties.end()) {
        if (id->second.type.isFloat) {
            fail(std::string("vertex property '") + kParticleIdName + "' has type " +
                 id->second.type.name + ", expected an integer type");
        }
        std::vector<std::int64_t> ids(vertexCount);
        for (std::size_t i = 0; i < vertexCount; ++i) {
            ids[i] = loadPlyValue<std::int64_t>(
                bytes.data() + bodyStart + 1 + i * rowBytes + id->second.offset, id->second.type);
        }
        orderParticlesById(particles, ids, path);
    }
    return particles;
}

HostParticles readCsv(const std::string& path) {
    const std::string bytes = readFileBytes(path);
    const auto fail = [&](const std::string& what) { malformed(path, what); };
    if (bytes.empty() || bytes.back() != '\n') {
        fail("truncated: the file does not end with a newline");
    }
    auto lines = split(std::string_view(bytes).substr(0, bytes.size() - 1), '\n');
    const auto names = particleColumnNames();
    std::string expectedHeader;
    for (const std::string& name : names) {
        expectedHeader += (expectedHeader.empty() ? "" : ",") + name;
    }
    const std::string headerWithIds = expectedHeader + "," + kParticleIdName;
    lines[0] = withoutCarriageReturn(lines[0]);
    const bool hasIds = lines[0] == headerWithIds;
    if (lines[0] != expectedHeader && !hasIds) {
        fail("header is '" + std::string(lines[0]) + "', expected '" + headerWithIds +
             "' (or, from weir before ids, '" + expectedHeader + "')");
    }
    HostParticles particles;
    std::vector<std::int64_t> ids;
    const auto columns = mutableParticleColumns(particles);
    const std::size_t expectedValues = columns.size() + (hasIds ? 1 : 0);
    for (std::size_t l = 1; l < lines.size(); ++l) {
        const std::string where = "line " + std::to_string(l + 1);
        const auto values = split(withoutCarriageReturn(lines[l]), ',');
        if (values.size() != expectedValues) {
            fail(where + " has " + std::to_string(values.size()) + " values, expected " +
                 std::to_string(expectedValues));
        }
        for (std::size_t c = 0; c < columns.size(); ++c) {
            Real value;
            if (!parseNumber(values[c], value)) {
                fail(where + ", column '" + names[c] + "': '" + std::string(values[c]) +
                     "' is not a number");
            }
            columns[c]->push_back(value);
        }
        if (hasIds) {
            std::int64_t id;
            if (!parseNumber(values.back(), id)) {
                fail(where + ", column '" + kParticleIdName + "': '" + std::string(values.back()) +
                     "' is not an integer");
            }
            ids.push_back(id);
        }
    }
    if (hasIds) {
        orderParticlesById(particles, ids, path);
    }
    return particles;
}

void orderParticlesById(HostParticles& particles, const std::vector<std::int64_t>& ids,
                        const std::string& path) {
    const std::size_t n = particles.size();
    if (ids.size() != n) {
        malformed(path, std::to_string(ids.size()) + " particle ids for " + std::to_string(n) +
                            " particles");
    }
    constexpr std::int64_t kMaxId = 2147483647;
    bool dense = true;  // ids 0 .. n - 1 (a run without emitters and sinks)
    for (std::size_t row = 0; row < n; ++row) {
        const std::int64_t id = ids[row];
        if (id < 0 || id > kMaxId) {
            malformed(path, "particle " + std::to_string(row) + " has id " + std::to_string(id) +
                                " (allowed: 0.." + std::to_string(kMaxId) + ", one per particle)");
        }
        dense = dense && std::uint64_t(id) < n;
    }
    // order: the rows in increasing id order; two equal neighbours there are a repeated id.
    std::vector<std::size_t> order(n);
    for (std::size_t row = 0; row < n; ++row) {
        order[row] = row;
    }
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return ids[a] < ids[b] || (ids[a] == ids[b] && a < b);
    });
    bool inOrder = true;
    for (std::size_t k = 0; k < n; ++k) {
        if (k > 0 && ids[order[k]] == ids[order[k - 1]]) {
            malformed(path, "particles " + std::to_string(order[k - 1]) + " and " +
                                std::to_string(order[k]) + " have the same id " +
                                std::to_string(ids[order[k]]) + " (ids must be unique)");
        }
        inOrder = inOrder && order[k] == k;
    }
    if (!dense) {  // ids with gaps (emitters and sinks): kept beside the particles
        particles.id.resize(n);
        for (std::size_t k = 0; k < n; ++k) {
            particles.id[k] = Index(ids[order[k]]);
        }
    } else {
        particles.id.clear();
    }
    if (inOrder) {
        return;
    }
    std::vector<Real> sorted(n);
    for (std::vector<Real>* column : mutableParticleColumns(particles)) {
        for (std::size_t k = 0; k < n; ++k) {
            sorted[k] = (*column)[order[k]];
        }
        column->swap(sorted);
    }
}

void checkFramePositions(const HostParticles& particles, const std::string& path) {
    const std::vector<Real>* axes[3] = {&particles.x, &particles.y, &particles.z};
    const char* names[3] = {"x", "y", "z"};
    const std::size_t n = particles.size();
    auto refuse = [&](std::size_t i, int axis, const std::string& why) {
        malformed(path, "particle " + std::to_string(i) + " of " + std::to_string(n) + " has " +
                            names[axis] + " = " + numberText((*axes[axis])[i]) + " (" + why + ")");
    };
    for (std::size_t i = 0; i < n; ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            const Real value = (*axes[axis])[i];
            if (!std::isfinite(value)) {
                refuse(i, axis, "positions must be finite numbers");
            }
            if (std::fabs(value) > kMaxFrameCoordinate) {
                refuse(i, axis,
                       "positions must lie within " + numberText(kMaxFrameCoordinate) +
                           " m of the origin");
            }
        }
    }
    // The plausible extent from a sample of at most 65536 particles, so a few flung far away
    // (or a whole frame gone wrong) do not widen it.
    const std::size_t stride = std::max<std::size_t>(1, n / 65536);
    double extent = 1.0;
    std::vector<Real> sample;
    for (int axis = 0; axis < 3 && n > 0; ++axis) {
        sample.clear();
        for (std::size_t i = 0; i < n; i += stride) {
            sample.push_back((*axes[axis])[i]);
        }
        const std::size_t lo = sample.size() / 100;
        const std::size_t hi = sample.size() - 1 - sample.size() / 100;
        std::nth_element(sample.begin(), sample.begin() + lo, sample.end());
        extent = std::max(extent, std::fabs(double(sample[lo])));
        std::nth_element(sample.begin(), sample.begin() + hi, sample.end());
        extent = std::max(extent, std::fabs(double(sample[hi])));
    }
    const double limit = kAbsurdExtentFactor * extent;
    for (std::size_t i = 0; i < n; ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            if (std::fabs((*axes[axis])[i]) > limit) {
                refuse(i, axis,
                       "more than 1e6 times the frame's plausible extent " + numberText(extent) +
                           " m from the origin");
            }
        }
    }
}

}  // namespace weir
