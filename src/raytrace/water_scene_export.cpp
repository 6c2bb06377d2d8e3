// Writers of the water look's export: OBJ, Radiance RGBE, PFM and JSON, each a few lines.
#include "raytrace/water_scene_export.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "raytrace/sky.h"

namespace weir {

namespace {

std::ofstream openForWriting(const std::string& path) {
    std::ofstream out(path, std::ios::binary);
    if (!out) {
        throw std::runtime_error("cannot write " + path);
    }
    return out;
}

void finish(std::ofstream& out, const std::string& path) {
    out.close();
    if (!out) {
        throw std::runtime_error("writing " + path + " failed");
    }
}

std::string json(const Vec3f& v) {
    std::ostringstream s;
    s << std::setprecision(9) << "[" << v.x << ", " << v.y << ", " << v.z << "]";
    return s.str();
}

// One pixel as Radiance's shared-exponent bytes: mantissas of the largest channel in 128..255.
void rgbe(const Vec3f& c, std::uint8_t out[4]) {
    const float largest = std::max({c.x, c.y, c.z});
    if (!(largest > 1e-32f)) {
        out[0] = out[1] = out[2] = out[3] = 0;
        return;
    }
    int exponent = 0;
    const float scale = std::frexp(largest, &exponent) * 256.0f / largest;
    for (int k = 0; k < 3; ++k) {
        out[k] = std::uint8_t(std::clamp(std::lround(std::max(0.0f, c[k]) * scale), 0L, 255L));
    }
    out[3] = std::uint8_t(exponent + 128);
}

}  // namespace

std::size_t writeTracedWaterObj(const std::string& path, const TracingScene& scene) {
    std::ofstream out = openForWriting(path);
    out << "# weir: the water triangles as the water look traces them (v, vn per corner)\n";
    out << std::setprecision(9);
    const std::vector<TriangleShading>& shading = scene.shading();
    const BvhView bvh = scene.bvh().view();
    std::size_t triangles = 0;
    for (std::size_t k = 0; k < shading.size(); ++k) {
        if (shading[k].kind != TriangleKind::Water) {
            continue;
        }
        const BvhTriangle& t = bvh.triangles[k];
        for (const Vec3f& p : {t.v0, t.v0 + t.e1, t.v0 + t.e2}) {
            out << "v " << p.x << " " << p.y << " " << p.z << "\n";
        }
        for (const Vec3f* n : {&shading[k].n0, &shading[k].n1, &shading[k].n2}) {
            out << "vn " << n->x << " " << n->y << " " << n->z << "\n";
        }
        ++triangles;
    }
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::size_t a = 3 * t + 1;
        out << "f " << a << "//" << a << " " << a + 1 << "//" << a + 1 << " " << a + 2 << "//"
            << a + 2 << "\n";
    }
    finish(out, path);
    return triangles;
}

void writeSkyHdr(const std::string& path, const WaterLook& look, int width) {
    if (width < 8 || width > 32767 || width % 2 != 0) {
        throw std::invalid_argument("sky image width " + std::to_string(width) +
                                    ": must be even, within 8..32767");
    }
    const int height = width / 2;
    std::ofstream out = openForWriting(path);
    out << "#?RADIANCE\n# weir: the water look's sky without the sun's disc\n"
        << "FORMAT=32-bit_rle_rgbe\n\n-Y " << height << " +X " << width << "\n";
    std::vector<std::uint8_t> row(4 * std::size_t(width));
    for (int r = 0; r < height; ++r) {
        const double elevation = kPiF / 2 - kPiF * (r + 0.5) / height;
        for (int c = 0; c < width; ++c) {
            const double azimuth = 2 * kPiF * (c + 0.5) / width - kPiF;
            const Vec3f d(float(std::cos(elevation) * std::cos(azimuth)),
                          float(std::sin(elevation)),
                          float(std::cos(elevation) * std::sin(azimuth)));
            rgbe(skyRadiance(look, d, false), &row[4 * std::size_t(c)]);
        }
        // A run-length scanline with literal runs only: readers take it whatever the bytes.
        const std::uint8_t head[4] = {2, 2, std::uint8_t(width >> 8), std::uint8_t(width & 255)};
        out.write(reinterpret_cast<const char*>(head), 4);
        for (int channel = 0; channel < 4; ++channel) {
            for (int start = 0; start < width; start += 128) {
                const int count = std::min(128, width - start);
                out.put(char(count));
                for (int c = start; c < start + count; ++c) {
                    out.put(char(row[4 * std::size_t(c) + std::size_t(channel)]));
                }
            }
        }
    }
    finish(out, path);
}

void writeRadiancePfm(const std::string& path, const std::vector<Vec3f>& radiance, int width,
                      int height) {
    if (radiance.size() != std::size_t(width) * std::size_t(height)) {
        throw std::invalid_argument("PFM of " + std::to_string(width) + " x " +
                                    std::to_string(height) + " pixels from " +
                                    std::to_string(radiance.size()) + " values");
    }
    std::ofstream out = openForWriting(path);
    out << "PF\n" << width << " " << height << "\n-1.0\n";  // negative scale: little-endian
    // PFM's rows run from the bottom.
    for (int y = height - 1; y >= 0; --y) {
        for (int x = 0; x < width; ++x) {
            const Vec3f& c = radiance[std::size_t(y) * std::size_t(width) + std::size_t(x)];
            const float rgb[3] = {c.x, c.y, c.z};
            for (float v : rgb) {
                std::uint8_t bytes[4];
                std::uint32_t bits;
                std::memcpy(&bits, &v, 4);
                for (int b = 0; b < 4; ++b) {
                    bytes[b] = std::uint8_t(bits >> (8 * b));
                }
                out.write(reinterpret_cast<const char*>(bytes), 4);
            }
        }
    }
    finish(out, path);
}

void writeWaterSceneJson(const std::string& path, const TracingScene& scene, const WaterLook& look,
                         const PinholeCamera& camera, int width, int height, int samples) {
    const TracingSceneView view = scene.view();
    std::ostringstream s;
    s << std::setprecision(9) << "{\n";
    s << "  \"camera\": {\"eye\": " << json(camera.eye) << ", \"forward\": " << json(camera.forward)
      << ", \"right\": " << json(camera.right) << ", \"up\": " << json(camera.up)
      << ", \"tanHalfFovY\": " << camera.tanHalfFovY << ", \"aspect\": " << camera.aspect << "},\n";
    s << "  \"width\": " << width << ", \"height\": " << height << ", \"samples\": " << samples
      << ",\n";
    s << "  \"containerLo\": " << json(view.containerLo)
      << ", \"containerHi\": " << json(view.containerHi) << ",\n";
    // The side walls that are there: [axis (0 x, 2 z), side (0 low, 1 high)].
    s << "  \"walls\": [";
    const char* separator = "";
    for (int axis : {0, 2}) {
        for (int side = 0; side < 2; ++side) {
            if ((view.walls & wallBit(axis, side)) != 0) {
                s << separator << "[" << axis << ", " << side << "]";
                separator = ", ";
            }
        }
    }
    s << "],\n";
    s << "  \"waterTriangles\": " << scene.waterTriangles()
      << ", \"contactTrianglesLeftOut\": " << scene.contactTrianglesLeftOut()
      << ", \"otherTriangles\": " << scene.shading().size() - scene.waterTriangles() << ",\n";
    s << "  \"look\": {\"refractiveIndex\": " << look.refractiveIndex
      << ", \"absorption\": " << json(look.absorption)
      << ", \"skyZenith\": " << json(look.skyZenith)
      << ", \"skyHorizon\": " << json(look.skyHorizon)
      << ", \"skyBelowHorizon\": " << json(look.skyBelowHorizon)
      << ", \"sunDirection\": " << json(normalized(look.sunDirection))
      << ", \"sunAngularRadius\": " << look.sunAngularRadius
      << ", \"sunIrradiance\": " << json(look.sunIrradiance)
      << ", \"sunDiscRadiance\": " << json(sunDiscRadiance(look))
      << ", \"sunGlow\": " << json(look.sunGlow)
      << ", \"sunGlowSharpness\": " << look.sunGlowSharpness
      << ", \"floorLight\": " << json(look.floorLight)
      << ", \"floorDark\": " << json(look.floorDark) << ", \"checkerSize\": " << look.checkerSize
      << ", \"groundAlbedo\": " << json(look.groundAlbedo)
      << ", \"wallAlbedo\": " << json(look.wallAlbedo)
      << ", \"obstacleAlbedo\": " << json(look.obstacleAlbedo)
      << ", \"bodyAlbedo\": " << json(look.bodyAlbedo)
      << ", \"maxSpecularBounces\": " << look.maxSpecularBounces
      << ", \"maxDiffuseBounces\": " << look.maxDiffuseBounces
      << ", \"exposure\": " << look.exposure << "}\n}\n";
    std::ofstream out = openForWriting(path);
    out << s.str();
    finish(out, path);
}

}  // namespace weir
