// Scene files: reading and validating scene JSON into a Scene, and the built-in scenes.
#include "scene/scene.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "scene/boundary.h"
#include "scene/embedded_scenes.h"
#include "scene/mesh_file.h"
#include "solver/methods.h"

namespace weir {
namespace {

using Json = nlohmann::json;
using Keys = std::initializer_list<std::string_view>;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr const char* kAxisNames[3] = {"x", "y", "z"};
// How deep arrays and objects may nest: a scene needs 4 levels; the reader and its messages
// recurse, so a file of 9,000 nested arrays would overflow the stack.
constexpr int kMaxJsonDepth = 64;
// Entries in each array of shapes: every seed is tested against every shape.
constexpr std::size_t kMaxShapes = 1024;
constexpr std::size_t kMaxMeshes = 64;
constexpr std::size_t kMaxMeshTriangles = 4000000;

std::string formatNumber(double v) {
    std::ostringstream out;
    out << std::setprecision(10) << v;
    return out.str();
}

std::string formatVec(const Vec3d& v) {
    std::ostringstream out;
    out << std::setprecision(10) << "[" << v.x << ", " << v.y << ", " << v.z << "]";
    return out.str();
}

std::string join(const auto& items, std::string_view separator) {
    std::string out;
    for (const auto& item : items) {
        if (!out.empty()) {
            out.append(separator);
        }
        out.append(std::string_view(item));
    }
    return out;
}

// Appends value as written (arrays spaced, objects compact), stopping once past 80 characters
// and at a few levels deep, so that no input makes a message long or deep to build.
void appendWritten(const Json& value, std::string& out, int depth, bool compact) {
    if (out.size() > 80) {
        return;
    }
    if (value.is_array() || value.is_object()) {
        const bool array = value.is_array();
        if (depth >= 8) {
            out += array ? "[...]" : "{...}";
            return;
        }
        out += array ? "[" : "{";
        bool first = true;
        for (auto it = value.begin(); it != value.end() && out.size() <= 80; ++it) {
            out += first ? "" : (compact || !array ? "," : ", ");
            first = false;
            if (!array) {
                out += Json(it.key()).dump() + ":";
            }
            appendWritten(*it, out, depth + 1, compact || !array);
        }
        out += array ? "]" : "}";
    } else {
        out += value.dump();
    }
}

// A JSON value as the user wrote it (give or take spacing), for messages; long values are cut.
std::string asWritten(const Json& value) {
    std::string text;
    appendWritten(value, text, 0, false);
    return text.size() > 80 ? text.substr(0, 77) + "..." : text;
}

// "line L, column C" of byte offset `at` in text (both from 1).
std::string lineAndColumn(const std::string& text, std::size_t at) {
    at = std::min(at, text.size());
    std::size_t line = 1, lineStart = 0;
    for (std::size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') {
            ++line;
            lineStart = i + 1;
        }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(at - lineStart + 1);
}

// Offset of the first array or object nested deeper than maxDepth, if any: a linear scan that
// skips strings and comments (malformed text is left for the parser to name).
std::optional<std::size_t> tooDeep(const std::string& text, int maxDepth) {
    int depth = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '"') {
            for (++i; i < text.size() && text[i] != '"'; ++i) {
                i += text[i] == '\\' ? 1 : 0;
            }
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            while (i < text.size() && text[i] != '\n') {
                ++i;
            }
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
            const std::size_t end = text.find("*/", i + 2);
            i = end == std::string::npos ? text.size() : end + 1;
        } else if (c == '[' || c == '{') {
            if (++depth > maxDepth) {
                return i;
            }
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return std::nullopt;
}

// A SAX handler that only notes where the text first fails to parse, with nlohmann's reason.
struct SyntaxCheck : nlohmann::json_sax<Json> {
    std::size_t at = 0;
    std::string reason;

    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override { return true; }
    bool key(string_t&) override { return true; }
    bool end_object() override { return true; }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t position, const std::string&,
                     const nlohmann::detail::exception& e) override {
        at = position > 0 ? position - 1 : 0;  // nlohmann counts the characters read
        reason = e.what();
        // Drop "[json.exception.parse_error.101] " and nlohmann's own "parse error at line L,
        // column C: " (ours names the place for every error, number overflow included).
        std::size_t cut = reason.find("] ");
        reason = cut == std::string::npos ? reason : reason.substr(cut + 2);
        if (reason.rfind("parse error", 0) == 0 && (cut = reason.find(": ")) != std::string::npos) {
            reason = reason.substr(cut + 2);
        }
        if (reason.find("number overflow") != std::string::npos) {
            reason += " (a number must be finite: at most about 1.8e308 in size)";
        }
        return false;
    }
};

// The JSON of a scene file, or a SceneError naming the file, line and column of what is wrong.
Json parseJson(const std::string& text, const std::string& source) {
    if (std::optional<std::size_t> at = tooDeep(text, kMaxJsonDepth)) {
        throw SceneError("scene '" + source + "': invalid JSON at " + lineAndColumn(text, *at) +
                         ": arrays and objects nested more than " + std::to_string(kMaxJsonDepth) +
                         " deep (a scene needs 4)");
    }
    SyntaxCheck check;
    if (!Json::sax_parse(text, &check, Json::input_format_t::json, /*strict=*/true,
                         /*ignore_comments=*/true)) {
        throw SceneError("scene '" + source + "': invalid JSON at " +
                         lineAndColumn(text, check.at) + ": " + check.reason);
    }
    try {
        return Json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
    } catch (const Json::exception& e) {
        throw SceneError("scene '" + source + "': invalid JSON: " + e.what());
    }
}

std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) {
        row[j] = j;
    }
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            std::size_t above = row[j];
            bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// A numeric rule: a range open or closed at each end, optionally integers only, and its text.
struct Range {
    double lo = -kInf, hi = kInf;
    bool loOpen = false, hiOpen = false;
    bool integer = false;
    std::string note;  // appended to the text, e.g. where a bound comes from

    bool contains(double v) const {
        return std::isfinite(v) && (loOpen ? v > lo : v >= lo) && (hiOpen ? v < hi : v <= hi) &&
               (!integer || v == std::floor(v));
    }
    std::string text() const {
        std::string kind = integer ? "an integer" : "a number";
        bool hasLo = lo > -kInf, hasHi = hi < kInf;
        if (!hasLo && !hasHi) {
            return "a finite number" + note;
        }
        if (hasLo && hasHi && !loOpen && !hiOpen) {
            return kind + " in [" + formatNumber(lo) + ", " + formatNumber(hi) + "]" + note;
        }
        std::string out = kind;
        if (hasLo) {
            out += (loOpen ? " > " : " >= ") + formatNumber(lo);
        }
        if (hasHi) {
            out += std::string(hasLo ? " and" : "") + (hiOpen ? " < " : " <= ") + formatNumber(hi);
        }
        return out + note;
    }
};

Range greaterThan(double lo) {
    Range range;
    range.lo = lo;
    range.loOpen = true;
    return range;
}
Range between(double lo, double hi) {
    Range range;
    range.lo = lo;
    range.hi = hi;
    return range;
}

// A number > 0 and at most hi.
Range positiveUpTo(double hi) {
    Range range = greaterThan(0);
    range.hi = hi;
    return range;
}

// Every number of a scene has bounds, so that nothing derived from it overflows a double, a float
// or an integer: positions within 1000 km of the origin, speeds under 100 km/s, gravity within
// 10,000 m/s^2 on each axis.
constexpr double kMaxCoordinate = 1e6;
const Range kCoordinate = between(-kMaxCoordinate, kMaxCoordinate);
const Range kLength = positiveUpTo(kMaxCoordinate);
const Range kVelocity = between(-1e5, 1e5);
const Range kGravity = between(-1e4, 1e4);

// Reads one JSON object of a scene file. It knows the object's JSON path ("blocks[1]") and the
// file's name, so every error names the file, the field, the value as written and what is
// allowed. Constructing one rejects non-objects and unknown keys (typos) at once.
class FieldReader {
   public:
    FieldReader(const Json& object, std::string path, const std::string& source, Keys allowed)
        : object_(object), path_(std::move(path)), source_(source) {
        std::string allowedText = join(allowed, ", ");
        if (!object.is_object()) {
            failAt(path_.empty() ? "the top level" : "field '" + path_ + "'", asWritten(object),
                   "an object with keys " + allowedText);
        }
        for (const auto& item : object.items()) {
            const std::string& key = item.key();
            if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) {
                continue;
            }
            std::string hint;
            for (std::string_view candidate : allowed) {
                if (editDistance(key, candidate) <= 2) {
                    hint = " (did you mean '" + std::string(candidate) + "'?)";
                    break;
                }
            }
            fail(pathOf(key), "an unknown key" + hint, "one of: " + allowedText);
        }
    }

    std::string pathOf(std::string_view key) const {
        return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
    }
    const std::string& path() const { return path_; }
    const Json* find(std::string_view key) const {
        auto it = object_.find(key);
        return it == object_.end() ? nullptr : &*it;
    }
    std::string written(std::string_view key) const {
        const Json* value = find(key);
        return value ? asWritten(*value) : "missing";
    }
    [[noreturn]] void fail(const std::string& field, const std::string& value,
                           const std::string& allowed) const {
        failAt("field '" + field + "'", value, allowed);
    }

    std::optional<double> optionalNumber(std::string_view key, const Range& range) const {
        const Json* value = find(key);
        if (!value) {
            return std::nullopt;
        }
        if (!value->is_number() || !range.contains(value->get<double>())) {
            fail(pathOf(key), asWritten(*value), range.text());
        }
        return value->get<double>();
    }
    double number(std::string_view key, const Range& range, double fallback) const {
        return optionalNumber(key, range).value_or(fallback);
    }
    double number(std::string_view key, const Range& range) const {
        require(key, range.text());
        return *optionalNumber(key, range);
    }

    // An array [x, y, z] of numbers, each in `range` (positions by default).
    Vec3d vec3(std::string_view key, std::optional<Vec3d> fallback = std::nullopt,
               const Range& range = kCoordinate) const {
        const std::string allowed = "an array of 3 finite numbers [x, y, z], each " + range.text();
        const Json* value = find(key);
        if (!value) {
            if (!fallback) {
                fail(pathOf(key), "missing", allowed);
            }
            return *fallback;
        }
        bool ok = value->is_array() && value->size() == 3;
        for (std::size_t i = 0; ok && i < 3; ++i) {
            ok = (*value)[i].is_number() && range.contains((*value)[i].get<double>());
        }
        if (!ok) {
            fail(pathOf(key), asWritten(*value), allowed);
        }
        return {(*value)[0].get<double>(), (*value)[1].get<double>(), (*value)[2].get<double>()};
    }

    bool boolean(std::string_view key, bool fallback) const {
        const Json* value = find(key);
        if (!value) {
            return fallback;
        }
        if (!value->is_boolean()) {
            fail(pathOf(key), asWritten(*value), "true or false");
        }
        return value->get<bool>();
    }

    std::string string(std::string_view key, const std::string& fallback) const {
        const Json* value = find(key);
        if (!value) {
            return fallback;
        }
        if (!value->is_string()) {
            fail(pathOf(key), asWritten(*value), "a string");
        }
        return value->get<std::string>();
    }

    // The object under key; an empty one (all defaults) when the key is absent.
    FieldReader object(std::string_view key, Keys allowed) const {
        static const Json kEmpty = Json::object();
        const Json* value = find(key);
        return FieldReader(value ? *value : kEmpty, pathOf(key), source_, allowed);
    }

    // Calls read(FieldReader) for each object of the array under key (absent: none), at most
    // maxItems of them.
    template <class Read>
    void forEach(std::string_view key, Keys allowed, Read&& read,
                 std::size_t maxItems = kMaxShapes) const {
        const Json* value = find(key);
        if (!value) {
            return;
        }
        if (!value->is_array() || value->size() > maxItems) {
            fail(pathOf(key),
                 value->is_array() ? "an array of " + std::to_string(value->size()) + " entries"
                                   : asWritten(*value),
                 "an array of objects with keys " + join(allowed, ", ") + " (at most " +
                     std::to_string(maxItems) + " of them)");
        }
        for (std::size_t i = 0; i < value->size(); ++i) {
            read(FieldReader((*value)[i], pathOf(key) + "[" + std::to_string(i) + "]", source_,
                             allowed));
        }
    }

    void require(std::string_view key, const std::string& allowed) const {
        if (!find(key)) {
            fail(pathOf(key), "missing", allowed);
        }
    }

   private:
    [[noreturn]] void failAt(const std::string& where, const std::string& value,
                             const std::string& allowed) const {
        throw SceneError("scene '" + source_ + "': " + where + " is " + value + ", must be " +
                         allowed);
    }

    const Json& object_;
    std::string path_;
    const std::string& source_;
};

Box readBox(const FieldReader& r) {
    Box box{r.vec3("min"), r.vec3("max")};
    for (int axis = 0; axis < 3; ++axis) {
        if (!(box.min[axis] < box.max[axis])) {
            r.fail(r.pathOf("max"), r.written("max"),
                   "greater than min " + r.written("min") + " on every axis (it is not on " +
                       kAxisNames[axis] + ")");
        }
    }
    return box;
}

SphereShape readSphere(const FieldReader& r) {
    return {r.vec3("center"), r.number("radius", kLength)};
}

// Fluid must start inside the container: says how far a shape's bounds stick out ("" if not).
std::string overhang(const Box& bounds, const Box& container) {
    Vec3d size = container.max - container.min;
    double tolerance = 1e-9 * std::max({size.x, size.y, size.z});
    std::vector<std::string> sides;
    for (int axis = 0; axis < 3; ++axis) {
        double below = container.min[axis] - bounds.min[axis];
        double above = bounds.max[axis] - container.max[axis];
        if (below > tolerance) {
            sides.push_back(formatNumber(below) + " on -" + kAxisNames[axis]);
        }
        if (above > tolerance) {
            sides.push_back(formatNumber(above) + " on +" + kAxisNames[axis]);
        }
    }
    return join(sides, ", ");
}

void requireInside(const FieldReader& r, const Box& bounds, const Box& container,
                   const std::string& value) {
    std::string out = overhang(bounds, container);
    if (!out.empty()) {
        r.fail(r.path(), value,
               "inside the container " + formatVec(container.min) + " to " +
                   formatVec(container.max) + " (it sticks out by " + out + ")");
    }
}

// A mesh {"file", "scale", "translate"} read and placed (obstacles.meshes[i], bodies[i].mesh), its
// triangles added to the scene's count, its inside test's index built.
MeshObstacle readMesh(const FieldReader& r, const std::string& source, std::size_t& meshTriangles) {
    MeshObstacle mesh;
    r.require("file", "an OBJ or STL file name");
    mesh.file = r.string("file", "");
    mesh.scale = r.number("scale", kLength, 1.0);
    mesh.translate = r.vec3("translate", Vec3d{});
    // Relative to the scene file's folder (the working directory for built-in scenes).
    std::filesystem::path file(mesh.file);
    if (file.is_relative() && source.find('<') != 0) {
        file = std::filesystem::path(source).parent_path() / file;
    }
    try {
        MeshData data = readMeshFile(file.string());
        for (const Vec3d& v : data.vertices) {
            mesh.vertices.push_back(v * mesh.scale + mesh.translate);
        }
        mesh.triangles = std::move(data.triangles);
    } catch (const std::runtime_error& e) {
        r.fail(r.pathOf("file"), r.written("file"),
               "a readable OBJ or STL file (" + file.string() + ": " + e.what() + ")");
    }
    for (const Vec3d& v : mesh.vertices) {
        for (int a = 0; a < 3; ++a) {
            if (!(std::fabs(v[a]) <= 10 * kMaxCoordinate)) {
                r.fail(r.pathOf("scale"), r.written("scale"),
                       "a scale that keeps the mesh " + file.string() + " within " +
                           formatNumber(10 * kMaxCoordinate) +
                           " m of the origin (a vertex lands at " + formatVec(v) + ")");
            }
        }
    }
    meshTriangles += mesh.triangles.size();
    if (meshTriangles > kMaxMeshTriangles) {
        r.fail(r.pathOf("file"), r.written("file"),
               "a mesh that keeps the scene's meshes at " + std::to_string(kMaxMeshTriangles) +
                   " triangles in all (" + file.string() + " brings them to " +
                   std::to_string(meshTriangles) + ")");
    }
    buildMeshIndex(mesh);
    return mesh;
}

// A mesh body's solid: its surface closed and facing outwards, its volume and centroid, and its
// bounds as the body's box.
void readMeshSolid(const FieldReader& m, BodySpec& body) {
    const std::string file = m.written("file");
    if (body.mesh.triangles.empty()) {
        m.fail(m.pathOf("file"), file, "a mesh with triangles that enclose the body (it has none)");
    }
    const std::size_t unmatched = unmatchedEdgesOf(body.mesh.vertices, body.mesh.triangles);
    if (unmatched > 0) {
        m.fail(m.pathOf("file"), file,
               "a closed surface, every edge shared by two triangles that run it opposite ways (" +
                   std::to_string(unmatched) +
                   " edges are not: a hole, a triangle facing the wrong way, or a seam whose "
                   "vertices differ), so that the body has an inside, a volume and a mass");
    }
    body.solid = meshSolidOf(body.mesh.vertices, body.mesh.triangles);
    Box bounds{body.mesh.vertices.front(), body.mesh.vertices.front()};
    for (const Vec3d& v : body.mesh.vertices) {
        for (int a = 0; a < 3; ++a) {
            bounds.min[a] = std::min(bounds.min[a], v[a]);
            bounds.max[a] = std::max(bounds.max[a], v[a]);
        }
    }
    const Vec3d size = bounds.max - bounds.min;
    const double boxVolume = size.x * size.y * size.z;
    if (!(body.solid.volume > 1e-9 * boxVolume)) {
        m.fail(
            m.pathOf("file"), file,
            body.solid.volume < 0
                ? "a surface whose triangles face outwards (counter-clockwise seen from outside); "
                  "these face inwards (signed volume " +
                      formatNumber(body.solid.volume) + " m^3): flip them"
                : "a surface that encloses a volume (this one encloses " +
                      formatNumber(body.solid.volume) + " m^3)");
    }
    body.box = bounds;
}

// "bodies": rigid bodies, floating or driven (BodySpec), each inside the container and clear of
// the others; they need the model and walls that couple them to the fluid.
void readBodies(const FieldReader& top, Scene& scene) {
    std::size_t meshTriangles = 0;
    for (const MeshObstacle& m : scene.obstacleMeshes) {
        meshTriangles += m.triangles.size();
    }
    top.forEach(
        "bodies",
        {"box", "sphere", "mesh", "density", "mass", "velocity", "angularVelocity", "motion"},
        [&](const FieldReader& r) {
            BodySpec body;
            const std::string shapes =
                "exactly one of \"box\": {\"min\": [..], \"max\": [..]}, "
                "\"sphere\": {\"center\": [..], \"radius\": r} or \"mesh\": {\"file\": "
                "\"hull.obj\", \"scale\": s, \"translate\": [..]}";
            const int given = (r.find("box") != nullptr) + (r.find("sphere") != nullptr) +
                              (r.find("mesh") != nullptr);
            if (given != 1) {
                r.fail(r.path(), given == 0 ? "a body with no shape" : "a body with two shapes",
                       shapes);
            }
            if (r.find("box") != nullptr) {
                body.box = readBox(r.object("box", {"min", "max"}));
            } else if (r.find("sphere") != nullptr) {
                body.isSphere = true;
                body.sphere = readSphere(r.object("sphere", {"center", "radius"}));
            } else {
                const FieldReader m = r.object("mesh", {"file", "scale", "translate"});
                body.isMesh = true;
                body.mesh = readMesh(m, scene.sourcePath, meshTriangles);
                readMeshSolid(m, body);
            }
            requireInside(r, body.bounds(), scene.container,
                          "a body with bounds " + formatVec(body.bounds().min) + " to " +
                              formatVec(body.bounds().max));
            body.velocity = r.vec3("velocity", Vec3d{}, kVelocity);
            body.angularVelocity = r.vec3("angularVelocity", Vec3d{}, kVelocity);
            if (r.find("motion") != nullptr) {
                FieldReader motion = r.object("motion", {"oscillate", "rotate"});
                if ((motion.find("oscillate") != nullptr) == (motion.find("rotate") != nullptr)) {
                    motion.fail(
                        motion.path(), motion.find("rotate") ? "both" : "neither",
                        "exactly one of \"oscillate\": {\"amplitude\": [..], \"period\": s, "
                        "\"ramp\": s} or \"rotate\": {\"rate\": [..]}");
                }
                if (motion.find("oscillate") != nullptr) {
                    FieldReader o = motion.object("oscillate", {"amplitude", "period", "ramp"});
                    body.drive = BodyDrive::Oscillate;
                    body.amplitude = o.vec3("amplitude", std::nullopt, kCoordinate);
                    body.period = o.number("period", positiveUpTo(1e6));
                    body.ramp = o.number("ramp", between(0, 1e6), 0.0);
                } else {
                    FieldReader o = motion.object("rotate", {"rate"});
                    body.drive = BodyDrive::Rotate;
                    body.rate = o.vec3("rate", std::nullopt, between(-1e4, 1e4));
                }
                // The body's reach over its motion: its bounds moved by the amplitude both ways,
                // or the circles its corners turn in. A piston that reaches past a wall would crush
                // the fluid caught between them.
                const Box start = body.bounds();
                Box swept = start;
                if (body.drive == BodyDrive::Oscillate) {
                    for (int a = 0; a < 3; ++a) {
                        swept.min[a] -= std::abs(body.amplitude[a]);
                        swept.max[a] += std::abs(body.amplitude[a]);
                    }
                } else if (!body.isSphere && length(body.rate) > 0) {  // a sphere stays put
                    // Each corner sweeps a circle about the axis through the centre: along world
                    // axis e it reaches para (a.e) +- perp sqrt(1 - (a.e)^2).
                    const Vec3d centre = body.centre();  // it turns about its centre of mass
                    const Vec3d axis = body.rate / length(body.rate);
                    swept = {centre, centre};
                    for (int c = 0; c < 8; ++c) {
                        const Vec3d corner((c & 1) ? start.max.x : start.min.x,
                                           (c & 2) ? start.max.y : start.min.y,
                                           (c & 4) ? start.max.z : start.min.z);
                        const Vec3d rel = corner - centre;
                        const double para = dot(rel, axis);
                        const double perp = length(rel - axis * para);
                        for (int a = 0; a < 3; ++a) {
                            const double ae = axis[a];
                            const double across = perp * std::sqrt(std::max(0.0, 1 - ae * ae));
                            swept.min[a] = std::min(swept.min[a], centre[a] + para * ae - across);
                            swept.max[a] = std::max(swept.max[a], centre[a] + para * ae + across);
                        }
                    }
                }
                const std::string out = overhang(swept, scene.container);
                if (!out.empty()) {
                    r.fail(r.pathOf("motion"),
                           "a motion that takes the body from " + formatVec(swept.min) + " to " +
                               formatVec(swept.max),
                           "a motion that keeps the body inside the container " +
                               formatVec(scene.container.min) + " to " +
                               formatVec(scene.container.max) + " (it reaches out by " + out + ")");
                }
                for (const char* key : {"density", "mass", "velocity", "angularVelocity"}) {
                    if (r.find(key) != nullptr) {
                        r.fail(r.pathOf(key), r.written(key),
                               "absent for a driven body (its \"motion\" sets where it is and "
                               "how fast it moves; the fluid does not push it back)");
                    }
                }
            } else {
                if ((r.find("density") != nullptr) == (r.find("mass") != nullptr)) {
                    r.fail(r.pathOf("density"),
                           r.find("density") ? "given with a mass" : "missing, and so is mass",
                           "exactly one of \"density\" (kg/m^3) or \"mass\" (kg) for a floating "
                           "body, or \"motion\" for a driven one");
                }
                body.mass = r.find("mass") != nullptr
                                ? r.number("mass", positiveUpTo(1e12))
                                : r.number("density", positiveUpTo(1e6)) * body.volume();
            }
            scene.bodies.push_back(body);
        },
        64);
    for (std::size_t a = 0; a < scene.bodies.size(); ++a) {
        for (std::size_t b = 0; b < a; ++b) {
            const Box p = scene.bodies[a].bounds(), q = scene.bodies[b].bounds();
            bool apart = false;
            for (int axis = 0; axis < 3; ++axis) {
                apart = apart || p.max[axis] <= q.min[axis] || q.max[axis] <= p.min[axis];
            }
            if (!apart) {
                top.fail("bodies[" + std::to_string(a) + "]",
                         "a body whose bounds " + formatVec(p.min) + " to " + formatVec(p.max) +
                             " overlap those of bodies[" + std::to_string(b) + "]",
                         "bodies apart at the start");
            }
        }
    }
    if (scene.bodies.empty()) {
        return;
    }
    const std::string what = "given only with ";
    if (scene.model != FluidModelName::DeltaSph) {
        top.fail("bodies", top.written("bodies"),
                 what + "\"fluid\": {\"model\": \"delta-sph\"} (bodies couple through its walls)");
    }
    if (scene.walls != WallModel::Particles) {
        top.fail("bodies", top.written("bodies"),
                 what + "\"walls\": {\"model\": \"particles\"} (bodies are boundary particles)");
    }
    if (!scene.solver.empty() && scene.solver != "wcsph") {
        top.fail("bodies", top.written("bodies"),
                 what + "the \"wcsph\" solver (not yet with \"" + scene.solver + "\")");
    }
    if (scene.periodic[0] || scene.periodic[1] || scene.periodic[2]) {
        top.fail("bodies", top.written("bodies"),
                 what + "walls all round (not yet in a container.periodic)");
    }
}

// "emitters" and "sinks" (issue 18): after the fluid model and solver, which they need.
void readFlow(const FieldReader& top, Scene& scene) {
    top.forEach(
        "emitters", {"disc", "rectangle", "direction", "speed", "rate", "start", "stop"},
        [&](const FieldReader& r) {
            EmitterSpec e;
            const std::string shapes =
                "exactly one of \"disc\": {\"center\": [..], \"radius\": r} or "
                "\"rectangle\": {\"center\": [..], \"size\": [a, b]}";
            if ((r.find("disc") != nullptr) == (r.find("rectangle") != nullptr)) {
                r.fail(r.path(),
                       r.find("disc") ? "both a disc and a rectangle"
                                      : "neither a disc nor a rectangle",
                       shapes);
            }
            e.direction = r.vec3("direction", std::nullopt, kVelocity);
            const double norm = length(e.direction);
            if (!(norm > 1e-12)) {
                r.fail(r.pathOf("direction"), r.written("direction"),
                       "a non-zero vector: the direction fluid comes in along");
            }
            e.direction = e.direction / norm;
            if (r.find("disc") != nullptr) {
                FieldReader d = r.object("disc", {"center", "radius"});
                e.center = d.vec3("center");
                e.radius = d.number("radius", kLength);
            } else {
                FieldReader q = r.object("rectangle", {"center", "size"});
                e.isDisc = false;
                e.center = q.vec3("center");
                const Json* size = q.find("size");
                const bool ok = size != nullptr && size->is_array() && size->size() == 2 &&
                                (*size)[0].is_number() && (*size)[1].is_number() &&
                                kLength.contains((*size)[0].get<double>()) &&
                                kLength.contains((*size)[1].get<double>());
                if (!ok) {
                    q.fail(q.pathOf("size"), q.written("size"),
                           "an array of 2 numbers [a, b], each " + kLength.text() +
                               ": the rectangle's sides (m)");
                }
                e.width = (*size)[0].get<double>();
                e.height = (*size)[1].get<double>();
            }
            if ((r.find("speed") != nullptr) == (r.find("rate") != nullptr)) {
                r.fail(r.pathOf("speed"),
                       r.find("speed") ? "given with a rate" : "missing, and so is rate",
                       "exactly one of \"speed\" (m/s) or \"rate\" (m^3/s)");
            }
            e.speed = r.find("speed") != nullptr ? r.number("speed", positiveUpTo(1e3))
                                                 : r.number("rate", positiveUpTo(1e6)) / e.area();
            if (!(e.speed <= 1e3)) {
                r.fail(r.pathOf("rate"), r.written("rate"),
                       "at most 1000 m/s through the emitter's area of " + formatNumber(e.area()) +
                           " m^2");
            }
            e.start = r.number("start", between(0, 1e9), 0.0);
            if (r.find("stop") != nullptr) {
                e.stop = r.number("stop", between(0, 1e9));
                if (!(e.stop > e.start)) {
                    r.fail(r.pathOf("stop"), r.written("stop"),
                           "after \"start\" (" + formatNumber(e.start) + " s)");
                }
            }
            // The emitting shape's bounds: a disc of radius R whose normal is n reaches
            // R sqrt(1 - n_a^2) along axis a; a rectangle reaches its corners.
            Box bounds{e.center, e.center};
            if (e.isDisc) {
                for (int a = 0; a < 3; ++a) {
                    const double reach =
                        e.radius * std::sqrt(std::max(0.0, 1 - e.direction[a] * e.direction[a]));
                    bounds.min[a] -= reach;
                    bounds.max[a] += reach;
                }
            } else {
                Vec3d u, v;
                e.planeAxes(u, v);
                for (int c = 0; c < 4; ++c) {
                    const Vec3d corner = e.center + u * (e.width * ((c & 1) ? 0.5 : -0.5)) +
                                         v * (e.height * ((c & 2) ? 0.5 : -0.5));
                    for (int a = 0; a < 3; ++a) {
                        bounds.min[a] = std::min(bounds.min[a], corner[a]);
                        bounds.max[a] = std::max(bounds.max[a], corner[a]);
                    }
                }
            }
            requireInside(r, bounds, scene.container,
                          "an emitter reaching from " + formatVec(bounds.min) + " to " +
                              formatVec(bounds.max));
            scene.emitters.push_back(e);
        },
        64);
    top.forEach(
        "sinks", {"min", "max"},
        [&](const FieldReader& r) {
            const Box box = readBox(r);
            bool overlaps = true;
            for (int a = 0; a < 3; ++a) {
                overlaps = overlaps && box.max[a] > scene.container.min[a] &&
                           box.min[a] < scene.container.max[a];
            }
            if (!overlaps) {
                r.fail(r.path(),
                       "a sink from " + formatVec(box.min) + " to " + formatVec(box.max) +
                           " outside the container",
                       "a box that overlaps the container " + formatVec(scene.container.min) +
                           " to " + formatVec(scene.container.max));
            }
            scene.sinks.push_back(box);
        },
        64);
    for (std::size_t k = 0; k < scene.emitters.size(); ++k) {
        for (std::size_t s = 0; s < scene.sinks.size(); ++s) {
            const Vec3d c = scene.emitters[k].center;
            const Box& b = scene.sinks[s];
            if (c.x >= b.min.x && c.x <= b.max.x && c.y >= b.min.y && c.y <= b.max.y &&
                c.z >= b.min.z && c.z <= b.max.z) {
                top.fail("emitters[" + std::to_string(k) + "]",
                         "an emitter centred at " + formatVec(c) + ", inside sinks[" +
                             std::to_string(s) + "] (what it lets in would leave at once)",
                         "an emitter outside every sink");
            }
        }
    }
    if (scene.emitters.empty() && scene.sinks.empty()) {
        return;
    }
    const char* key = scene.emitters.empty() ? "sinks" : "emitters";
    const std::string what = "given only with ";
    if (scene.model != FluidModelName::DeltaSph) {
        top.fail(key, top.written(key),
                 what + "\"fluid\": {\"model\": \"delta-sph\"} (not yet with the paper's model)");
    }
    if (!scene.solver.empty() && scene.solver != "wcsph") {
        top.fail(key, top.written(key),
                 what + "the \"wcsph\" solver (not yet with \"" + scene.solver + "\")");
    }
    if (scene.periodic[0] || scene.periodic[1] || scene.periodic[2]) {
        top.fail(key, top.written(key), what + "walls all round (not yet in a container.periodic)");
    }
}

std::optional<Integrator> integratorByName(const std::string& name) {
    if (name == "semi-implicit-euler") {
        return Integrator::SemiImplicitEuler;
    }
    if (name == "explicit-euler") {
        return Integrator::ExplicitEuler;
    }
    return std::nullopt;
}

Scene parseSceneNamed(const std::string& jsonText, const std::string& source,
                      const std::string& defaultName) {
    const Json root = parseJson(jsonText, source);

    FieldReader top(
        root, "", source,
        {"name", "description", "container", "blocks", "spheres", "obstacles", "bodies", "emitters",
         "sinks", "fluid", "particles", "gravity", "time", "walls", "limits", "solver", "dfsph"});
    Scene scene;
    scene.sourcePath = source;
    scene.json = root.dump();
    scene.name = top.string("name", defaultName);
    if (scene.name.empty()) {
        top.fail("name", "\"\"", "a non-empty string");
    }
    scene.description = top.string("description", "");

    top.require("container", "an object {\"min\": [x, y, z], \"max\": [x, y, z]}");
    FieldReader containerReader = top.object("container", {"min", "max", "periodic"});
    scene.container = readBox(containerReader);
    const Box& container = scene.container;
    if (const Json* periodic = containerReader.find("periodic")) {
        if (!periodic->is_array() || periodic->size() != 3 || !(*periodic)[0].is_boolean() ||
            !(*periodic)[1].is_boolean() || !(*periodic)[2].is_boolean()) {
            containerReader.fail(containerReader.pathOf("periodic"),
                                 containerReader.written("periodic"),
                                 "three booleans [x, y, z]: which axes wrap around");
        }
        for (int a = 0; a < 3; ++a) {
            scene.periodic[std::size_t(a)] = (*periodic)[std::size_t(a)].get<bool>();
        }
    }

    top.forEach("blocks", {"min", "max", "velocity"}, [&](const FieldReader& r) {
        FluidBlock block{readBox(r), r.vec3("velocity", Vec3d{}, kVelocity)};
        requireInside(r, block.box, container,
                      "{min " + r.written("min") + ", max " + r.written("max") + "}");
        scene.blocks.push_back(block);
    });
    top.forEach("spheres", {"center", "radius", "velocity"}, [&](const FieldReader& r) {
        FluidSphere fluid{readSphere(r), r.vec3("velocity", Vec3d{}, kVelocity)};
        const SphereShape& s = fluid.sphere;
        Vec3d extent{s.radius, s.radius, s.radius};
        requireInside(r, Box{s.center - extent, s.center + extent}, container,
                      "{center " + r.written("center") + ", radius " + r.written("radius") + "}");
        scene.spheres.push_back(fluid);
    });
    if (scene.blocks.empty() && scene.spheres.empty() && top.find("emitters") == nullptr) {
        top.fail("blocks", top.written("blocks"),
                 "a non-empty array of fluid blocks unless 'spheres' (" + top.written("spheres") +
                     ") holds fluid spheres or 'emitters' let fluid in: a scene needs fluid");
    }

    FieldReader obstacles = top.object("obstacles", {"boxes", "spheres", "meshes"});
    obstacles.forEach("boxes", {"min", "max"},
                      [&](const FieldReader& r) { scene.obstacleBoxes.push_back(readBox(r)); });
    obstacles.forEach("spheres", {"center", "radius"}, [&](const FieldReader& r) {
        scene.obstacleSpheres.push_back(readSphere(r));
    });
    std::size_t meshTriangles = 0;
    obstacles.forEach(
        "meshes", {"file", "scale", "translate"},
        [&](const FieldReader& r) {
            MeshObstacle mesh = readMesh(r, source, meshTriangles);
            scene.obstacleMeshes.push_back(std::move(mesh));
        },
        kMaxMeshes);

    FieldReader fluid = top.object(
        "fluid", {"preset", "restDensity", "viscosity", "stiffness", "eos", "pressureForce",
                  "clampNegativePressure", "negativePressureScale", "model", "artificialViscosity",
                  "densityDiffusion", "shifting", "tensileCorrection"});
    const std::string model = fluid.string("model", "delta-sph");
    if (model == "paper") {
        scene.model = FluidModelName::Paper;
    } else if (model == "delta-sph") {
        scene.model = FluidModelName::DeltaSph;
    } else {
        fluid.fail(fluid.pathOf("model"), fluid.written("model"),
                   "\"paper\" (Müller et al. 2003, the paper's) or \"delta-sph\" (Wendland "
                   "kernel, density diffusion, the fluid's own viscosity)");
    }
    const bool delta = scene.model == FluidModelName::DeltaSph;
    scene.artificialViscosity = fluid.optionalNumber("artificialViscosity", between(0, 1));
    scene.densityDiffusion = fluid.optionalNumber("densityDiffusion", between(0, 1));
    scene.shifting = fluid.optionalNumber("shifting", between(0, 10));
    scene.tensileCorrection = fluid.optionalNumber("tensileCorrection", between(0, 1));
    if (!delta) {
        for (const char* field :
             {"artificialViscosity", "densityDiffusion", "shifting", "tensileCorrection"}) {
            if (fluid.find(field)) {
                fluid.fail(fluid.pathOf(field), fluid.written(field),
                           "given only with \"model\": \"delta-sph\" (the paper's model has "
                           "none of artificialViscosity, densityDiffusion, shifting, "
                           "tensileCorrection)");
            }
        }
    }
    scene.preset = fluid.string("preset", "");
    if (!scene.preset.empty()) {
        const FluidPreset* preset = fluidPreset(scene.preset);
        if (preset == nullptr) {
            fluid.fail(fluid.pathOf("preset"), fluid.written("preset"),
                       "one of " + join(fluidPresetNames(), ", "));
        }
        scene.restDensity = preset->density;
        scene.physicalViscosity = preset->viscosity;
    }
    scene.restDensity = fluid.number("restDensity", positiveUpTo(1e5), scene.restDensity);
    Range viscosityRange = between(0, 1e6);
    viscosityRange.hiOpen = true;
    scene.viscosity = fluid.optionalNumber("viscosity", viscosityRange);
    Range stiffnessRange = positiveUpTo(1e12);
    stiffnessRange.note = " (a speed of sound up to 1e6 m/s)";
    scene.stiffness = fluid.optionalNumber("stiffness", stiffnessRange);
    scene.eosGiven = fluid.find("eos") != nullptr;
    std::string eos = fluid.string("eos", delta ? "tait" : "linear");
    if (eos == "linear") {
        scene.eos = EquationOfState::Linear;
    } else if (eos == "tait") {
        scene.eos = EquationOfState::Tait;
    } else {
        fluid.fail(fluid.pathOf("eos"), fluid.written("eos"),
                   "\"linear\" (the paper's eq. 3) or \"tait\" (gamma = 7)");
    }
    std::string pressureForce = fluid.string("pressureForce", "symmetric");
    if (pressureForce == "symmetric" || pressureForce == "paper") {
        scene.paperPressureForce = pressureForce == "paper";
    } else {
        fluid.fail(fluid.pathOf("pressureForce"), fluid.written("pressureForce"),
                   "\"symmetric\" (m (p_i / rho_i^2 + p_j / rho_j^2)) or \"paper\" (eq. 4)");
    }
    scene.clampNegativePressure =
        fluid.boolean("clampNegativePressure", scene.clampNegativePressure);
    if (delta && !fluid.find("clampNegativePressure")) {
        scene.clampNegativePressure = false;  // continuity density: no surface deficiency
    }
    scene.negativePressureScale = fluid.number("negativePressureScale", between(0, 1),
                                               scene.clampNegativePressure ? 0.0 : 1.0);
    if (fluid.find("clampNegativePressure") && fluid.find("negativePressureScale") &&
        scene.clampNegativePressure != (scene.negativePressureScale == 0)) {
        fluid.fail(fluid.pathOf("negativePressureScale"), fluid.written("negativePressureScale"),
                   std::string(scene.clampNegativePressure ? "0" : "above 0") +
                       " to agree with clampNegativePressure " +
                       fluid.written("clampNegativePressure") + ", or given without it");
    }
    scene.clampNegativePressure = scene.negativePressureScale == 0;

    FieldReader particles = top.object("particles", {"count", "spacing", "smoothingRatio"});
    if (particles.find("count") && particles.find("spacing")) {
        top.fail("particles", top.written("particles"),
                 "an object with at most one of 'count' and 'spacing'");
    }
    Range countRange = between(1, 2147483647.0);
    countRange.integer = true;
    if (auto count = particles.optionalNumber("count", countRange)) {
        scene.particleCount = static_cast<std::int64_t>(*count);
    }
    scene.spacing = particles.optionalNumber("spacing", kLength);

    scene.gravity = top.vec3("gravity", scene.gravity, kGravity);

    FieldReader time =
        top.object("time", {"duration", "frameRate", "timeStep", "integrator", "adaptive"});
    scene.duration = time.number("duration", positiveUpTo(1e6), scene.duration);
    // (A frame rate so low that a frame takes more than 1e9 steps fails at set-up.)
    scene.frameRate = time.number("frameRate", positiveUpTo(1e5), scene.frameRate);
    // A step longer than a frame could not land on frame times (one so short that a frame takes
    // more than 1e9 steps fails at set-up).
    Range stepRange = greaterThan(0);
    stepRange.hi = 1.0 / scene.frameRate;
    stepRange.note = " (1 / frameRate)";
    scene.timeStep = time.optionalNumber("timeStep", stepRange);
    if (time.find("adaptive")) {
        scene.adaptiveTimeStep = time.boolean("adaptive", true);
    }
    std::string integrator = time.string("integrator", "semi-implicit-euler");
    if (auto chosen = integratorByName(integrator)) {
        scene.integrator = *chosen;
    } else {
        time.fail(time.pathOf("integrator"), time.written("integrator"),
                  "one of \"semi-implicit-euler\", \"explicit-euler\"");
    }

    FieldReader walls = top.object("walls", {"model", "restitution", "friction", "slip", "moving"});
    std::string wallModel =
        walls.string("model", scene.obstacleMeshes.empty() && !delta ? "simple" : "particles");
    if (wallModel == "simple") {
        scene.walls = WallModel::Simple;
    } else if (wallModel == "particles") {
        scene.walls = WallModel::Particles;
    } else {
        walls.fail(walls.pathOf("model"), walls.written("model"),
                   "\"particles\" (boundary particles, Akinci et al. 2012) or \"simple\" (the "
                   "paper's collision response)");
    }
    if (scene.walls == WallModel::Simple && !scene.obstacleMeshes.empty()) {
        walls.fail(walls.pathOf("model"), walls.written("model"),
                   "\"particles\" when obstacles.meshes is given (mesh obstacles act through "
                   "boundary particles only)");
    }
    scene.wallRestitution = walls.number("restitution", between(0, 1), scene.wallRestitution);
    scene.wallFriction = walls.number("friction", between(0, 1), scene.wallFriction);
    const std::string slip = walls.string("slip", "no-slip");
    if (slip == "no-slip" || slip == "free-slip") {
        scene.noSlip = slip == "no-slip";
    } else {
        walls.fail(walls.pathOf("slip"), walls.written("slip"),
                   "\"no-slip\" (the fluid sticks to the walls) or \"free-slip\"");
    }
    walls.forEach("moving", {"face", "velocity"}, [&](const FieldReader& r) {
        r.require("face", "a container face: \"-x\", \"+x\", \"-y\", \"+y\", \"-z\" or \"+z\"");
        const std::string face = r.string("face", "");
        MovingWall moving;
        if (face.size() != 2 || (face[0] != '-' && face[0] != '+') || face[1] < 'x' ||
            face[1] > 'z') {
            r.fail(r.pathOf("face"), r.written("face"),
                   "one of \"-x\", \"+x\", \"-y\", \"+y\", \"-z\", \"+z\"");
        }
        moving.axis = face[1] - 'x';
        moving.side = face[0] == '+' ? 1 : 0;
        moving.velocity = r.vec3("velocity", std::nullopt, kVelocity);
        if (moving.velocity[moving.axis] != 0) {
            r.fail(r.pathOf("velocity"), r.written("velocity"),
                   "a velocity along the face (its " + std::string(1, face[1]) +
                       " component 0: the wall slides, its particles stay put)");
        }
        scene.movingWalls.push_back(moving);
    });
    if (!scene.movingWalls.empty() && scene.walls != WallModel::Particles) {
        walls.fail(walls.pathOf("moving"), walls.written("moving"),
                   "given only with \"model\": \"particles\" (moving walls are boundary "
                   "particles with a velocity)");
    }

    FieldReader limits = top.object("limits", {"maxSpeed", "maxCompression"});
    scene.maxSpeed = limits.optionalNumber("maxSpeed", positiveUpTo(1e8));
    scene.maxCompression = limits.number("maxCompression", positiveUpTo(1e3), scene.maxCompression);

    scene.solver = top.string("solver", "");
    try {
        scene.solver = checkPressureSolver(scene.solver);
    } catch (const std::invalid_argument& e) {
        const std::string allowed = e.what();
        top.fail("solver", top.written("solver"),
                 allowed.substr(allowed.find("allowed are ") + 12));
    }
    // After the model and the solver, whose default it follows.
    scene.smoothingRatio = particles.number("smoothingRatio", between(1.2, 5),
                                            defaultSmoothingRatio(scene.model, scene.solver));
    FieldReader dfsph = top.object(
        "dfsph", {"densityError", "divergenceError", "worstDensityError", "maxSweeps", "cfl"});
    Scene::DfsphSettings& settings = scene.dfsph;
    settings.densityErrorPercent =
        dfsph.number("densityError", positiveUpTo(10), settings.densityErrorPercent);
    settings.divergenceErrorPercent =
        dfsph.number("divergenceError", between(0, 100), settings.divergenceErrorPercent);
    settings.worstDensityErrorPercent =
        dfsph.number("worstDensityError", between(0, 100), settings.worstDensityErrorPercent);
    Range sweeps = between(2, 10000);
    sweeps.integer = true;
    settings.maxSweeps = int(dfsph.number("maxSweeps", sweeps, settings.maxSweeps));
    settings.cfl = dfsph.number("cfl", positiveUpTo(2), settings.cfl);
    readBodies(top, scene);
    readFlow(top, scene);
    return scene;
}

}  // namespace

double EmitterSpec::area() const { return isDisc ? kPi * radius * radius : width * height; }

void EmitterSpec::planeAxes(Vec3d& u, Vec3d& v) const {
    const Vec3d n = direction;
    Vec3d ref = std::abs(n.x) > 0.999 ? Vec3d(0, 0, 1) : Vec3d(1, 0, 0);
    u = ref - n * dot(ref, n);
    u = u / length(u);
    v = cross(n, u);
}

double BodySpec::volume() const {
    if (isMesh) {
        return solid.volume;
    }
    if (isSphere) {
        return 4.0 / 3.0 * 3.14159265358979323846 * sphere.radius * sphere.radius * sphere.radius;
    }
    const Vec3d size = box.max - box.min;
    return size.x * size.y * size.z;
}

const FluidPreset* fluidPreset(const std::string& name) {
    // Handbook values near 20 C (CRC Handbook of Chemistry and Physics; honey varies with water
    // content, 2-10 Pa s: the middle of the range).
    static const FluidPreset kPresets[] = {
        {"water", 998.0, 1.0e-3, "CRC Handbook, water at 20 C"},
        {"oil", 911.0, 0.084, "CRC Handbook, olive oil at 20 C"},
        {"honey", 1420.0, 6.0, "honey at 20 C, 17% water (2-10 Pa s by water content)"},
    };
    for (const FluidPreset& preset : kPresets) {
        if (name == preset.name) {
            return &preset;
        }
    }
    return nullptr;
}

std::vector<std::string> fluidPresetNames() { return {"water", "oil", "honey"}; }

Scene parseScene(const std::string& jsonText, const std::string& sourceName) {
    std::string stem = std::filesystem::path(sourceName).stem().string();
    return parseSceneNamed(jsonText, sourceName, stem.empty() ? "scene" : stem);
}

Scene loadScene(const std::string& path) {
    auto fail = [&](const char* what, int error) {
        throw SceneError("scene '" + path + "': cannot " + what +
                         " the file: " + std::generic_category().message(error));
    };
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                         &std::fclose);
    if (!file) {
        fail("open", errno);
    }
    std::string text;
    char buffer[1 << 16];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, file.get())) {
        text.append(buffer, n);
    }
    if (std::ferror(file.get())) {
        fail("read", errno);  // e.g. a directory: EISDIR
    }
    return parseScene(text, path);
}

Scene withFluidModel(const Scene& scene, const std::string& model) {
    Json root = Json::parse(scene.json);
    root["fluid"]["model"] = model;
    return parseSceneNamed(root.dump(), scene.sourcePath, scene.name);
}

double defaultSmoothingRatio(FluidModelName model, const std::string& solver) {
    return model == FluidModelName::DeltaSph && (solver.empty() || solver == "wcsph") ? 3.0 : 2.0;
}

Scene withSolver(const Scene& scene, const std::string& solver) {
    Json root = Json::parse(scene.json);
    root["solver"] = solver;
    return parseSceneNamed(root.dump(), scene.sourcePath, scene.name);
}

Scene withOverrides(const Scene& scene, const std::string& patchJson) {
    Json patch;
    try {
        patch = Json::parse(patchJson);
    } catch (const Json::parse_error& e) {
        throw SceneError("overrides of scene '" + scene.name + "': not JSON: " + e.what());
    }
    if (!patch.is_object()) {
        throw SceneError("overrides of scene '" + scene.name + "': " + asWritten(patch) +
                         " is not allowed; give an object of scene fields, e.g. "
                         "{\"fluid\": {\"viscosity\": 0.01}}");
    }
    Json root = Json::parse(scene.json);
    root.merge_patch(patch);
    return parseSceneNamed(root.dump(), scene.sourcePath, scene.name);
}

Scene builtinScene(const std::string& name) {
    for (const auto& [stem, text] : embeddedSceneFiles()) {
        if (stem == name) {
            return parseSceneNamed(text, "<built-in " + name + ">", name);
        }
    }
    throw SceneError("unknown built-in scene '" + name + "'" + didYouMeanBuiltinScene(name) +
                     ", available: " + join(builtinSceneNames(), ", "));
}

std::string didYouMeanBuiltinScene(const std::string& name) {
    // The nearest name by edit distance, if near enough to be a slip; else one that holds the
    // name ("pool": drop_into_pool).
    std::string best;
    std::size_t bestDistance = std::max<std::size_t>(2, name.size() * 2 / 5) + 1;
    for (const std::string& candidate : builtinSceneNames()) {
        const std::size_t d = editDistance(name, candidate);
        if (d < bestDistance) {
            best = candidate;
            bestDistance = d;
        }
    }
    if (best.empty() && name.size() >= 3) {
        for (const std::string& candidate : builtinSceneNames()) {
            if (candidate.find(name) != std::string::npos) {
                best = candidate;
                break;
            }
        }
    }
    return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

std::vector<std::string> builtinSceneNames() {
    std::vector<std::string> names;
    for (const auto& entry : embeddedSceneFiles()) {
        names.push_back(entry.first);
    }
    return names;
}

Scene resolveScene(const std::string& spec) {
    if (spec.empty()) {
        return builtinScene("dam_break");
    }
    // A folder of that name (say out/dam_break/ seen from out/) does not hide a built-in scene.
    if (std::filesystem::exists(spec) && !std::filesystem::is_directory(spec)) {
        return loadScene(spec);
    }
    for (const std::string& name : builtinSceneNames()) {
        if (spec == name) {
            return builtinScene(name);
        }
    }
    std::string names;
    for (const std::string& name : builtinSceneNames()) {
        names += (names.empty() ? "" : ", ") + name;
    }
    const std::filesystem::path path(spec);
    if (spec.find('/') != std::string::npos || path.has_extension()) {
        // Meant as a file: say that it is missing, and name a built-in scene it may stand for.
        try {
            return loadScene(spec);
        } catch (const SceneError& e) {
            const std::string hint = didYouMeanBuiltinScene(path.stem().string());
            throw SceneError(
                std::string(e.what()) +
                (hint.empty() ? "" : "; a built-in scene is named without a path or .json" + hint));
        }
    }
    throw SceneError("scene '" + spec + "': no such file, and no built-in scene of that name" +
                     didYouMeanBuiltinScene(spec) + "; the built-in scenes are " + names +
                     " (weir info lists them)");
}

}  // namespace weir
