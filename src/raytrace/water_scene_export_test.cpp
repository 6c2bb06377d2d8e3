// The water look's export: the OBJ holds exactly the traced water triangles (those on the floor
// left out) with their normals, the sky image decodes to the sky's radiance, the PFM to the
// radiance given.
#include "raytrace/water_scene_export.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "raytrace/sky.h"

namespace weir {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "weir_water_scene_export_test";
    fs::create_directories(dir);
    return dir / name;
}

// Two triangles of water: one lying on the container's floor facing down (left out), one above.
TriangleMesh twoTriangles() {
    TriangleMesh mesh;
    mesh.positions = {{0.2f, 0.001f, 0.2f}, {0.4f, 0.001f, 0.2f}, {0.2f, 0.001f, 0.4f},
                      {0.2f, 0.5f, 0.2f},   {0.2f, 0.5f, 0.4f},   {0.4f, 0.5f, 0.2f}};
    mesh.normals = {{0, -1, 0}, {0, -1, 0}, {0, -1, 0}, {0, 1, 0}, {0, 1, 0}, {0.6f, 0.8f, 0}};
    mesh.indices = {0, 1, 2, 3, 4, 5};
    return mesh;
}

TEST(WaterSceneExport, TheObjHoldsTheTracedWaterTriangles) {
    const TriangleMesh mesh = twoTriangles();
    TracingSceneDescription d;
    d.water = &mesh;
    d.container = {{0, 0, 0}, {1, 1, 1}};
    d.cameraEye = {3, 2, 3};
    d.contactDistance = 0.01;
    d.obstacleBoxes = {{{0.6, 0, 0.6}, {0.7, 0.1, 0.7}}};  // not written
    const TracingScene scene(d);
    ASSERT_EQ(scene.contactTrianglesLeftOut(), 1U);
    const fs::path path = scratch("water.obj");
    EXPECT_EQ(writeTracedWaterObj(path.string(), scene), 1U);

    std::istringstream lines(readAll(path));
    std::vector<Vec3f> v, vn;
    std::vector<std::string> faces;
    for (std::string line; std::getline(lines, line);) {
        std::istringstream words(line);
        std::string kind;
        words >> kind;
        Vec3f p;
        if (kind == "v" || kind == "vn") {
            words >> p.x >> p.y >> p.z;
            (kind == "v" ? v : vn).push_back(p);
        } else if (kind == "f") {
            faces.push_back(line);
        }
    }
    ASSERT_EQ(v.size(), 3U);
    ASSERT_EQ(vn.size(), 3U);
    ASSERT_EQ(faces.size(), 1U);
    EXPECT_EQ(faces[0], "f 1//1 2//2 3//3");
    // The upper triangle, wound as given, its normals unit.
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(length(v[c] - mesh.positions[3 + c]), 0.0f, 1e-6f);
        EXPECT_NEAR(length(vn[c] - normalized(mesh.normals[3 + c])), 0.0f, 1e-6f);
    }
}

TEST(WaterSceneExport, TheSkyImageDecodesToTheSky) {
    const WaterLook look;
    const int width = 64, height = 32;
    const fs::path path = scratch("sky.hdr");
    writeSkyHdr(path.string(), look, width);
    const std::string data = readAll(path);
    const std::string size = "\n-Y 32 +X 64\n";
    const std::size_t start = data.find(size);
    ASSERT_NE(start, std::string::npos);
    ASSERT_EQ(data.rfind("#?RADIANCE", 0), 0U);
    std::size_t at = start + size.size();
    for (int r = 0; r < height; ++r) {
        // A run-length scanline of literal runs: 2, 2, width, then each channel in runs.
        ASSERT_EQ(std::uint8_t(data[at]), 2);
        ASSERT_EQ(std::uint8_t(data[at + 3]), width);
        at += 4;
        std::vector<std::uint8_t> channels(4 * width);
        for (int channel = 0; channel < 4; ++channel) {
            for (int c = 0; c < width;) {
                const int count = std::uint8_t(data[at++]);
                ASSERT_LE(count, 128);
                for (int k = 0; k < count; ++k, ++c) {
                    channels[std::size_t(channel * width + c)] = std::uint8_t(data[at++]);
                }
            }
        }
        const double elevation = kPiF / 2 - kPiF * (r + 0.5) / height;
        for (int c = 0; c < width; c += 7) {
            const double azimuth = 2 * kPiF * (c + 0.5) / width - kPiF;
            const Vec3f d(float(std::cos(elevation) * std::cos(azimuth)),
                          float(std::sin(elevation)),
                          float(std::cos(elevation) * std::sin(azimuth)));
            const Vec3f sky = skyRadiance(look, d, false);
            const int e = channels[std::size_t(3 * width + c)];
            for (int k = 0; k < 3; ++k) {
                const float decoded =
                    std::ldexp(float(channels[std::size_t(k * width + c)]), e - 128 - 8);
                // 8-bit mantissas of the largest channel's exponent: within 1/256 of it.
                EXPECT_NEAR(decoded, sky[k], 2.0f / 256 * largestOf(sky)) << r << " " << c;
            }
        }
    }
    EXPECT_EQ(at, data.size());
}

TEST(WaterSceneExport, ThePfmHoldsTheRadianceRowsFromTheBottom) {
    const std::vector<Vec3f> radiance = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {0.5f, 0.25f, 0.125f}};
    const fs::path path = scratch("image.pfm");
    writeRadiancePfm(path.string(), radiance, 2, 2);
    const std::string data = readAll(path);
    const std::string header = "PF\n2 2\n-1.0\n";
    ASSERT_EQ(data.size(), header.size() + 4 * 3 * 4);
    ASSERT_EQ(data.substr(0, header.size()), header);
    float first[3];
    std::memcpy(first, data.data() + header.size(), sizeof first);  // little-endian host
    // The bottom row's first pixel.
    EXPECT_EQ(first[0], 7.0f);
    EXPECT_EQ(first[2], 9.0f);
    EXPECT_THROW(writeRadiancePfm(path.string(), radiance, 3, 2), std::invalid_argument);
}

}  // namespace
}  // namespace weir
