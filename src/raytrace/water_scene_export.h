// What the water look traces, written out for another renderer to draw the same picture
// (src/python/water_look_cycles_test.py renders it in Blender Cycles): the water's triangles as
// traced, the camera, container, walls and constants, the sky as an image, and the image's linear
// radiance before tone mapping. All in weir's coordinates (metres, y up).
#pragma once

#include <string>
#include <vector>

#include "raytrace/path_tracer.h"
#include "raytrace/tracing_scene.h"
#include "raytrace/water_look.h"

namespace weir {

// The water triangles of `scene` exactly as traced (those on the floor and walls left out) as a
// Wavefront OBJ triangle soup: three `v` and three `vn` (the unit shading normals) per triangle,
// wound as traced (counter-clockwise seen from outside the water). Returns the triangle count.
// Throws std::runtime_error when the file cannot be written.
std::size_t writeTracedWaterObj(const std::string& path, const TracingScene& scene);

// The sky without the sun's disc (what a path meets after a matte bounce) as an equirectangular
// Radiance RGBE image (.hdr) of width x width/2 pixels. Column c's centre lies at azimuth
// atan2(z, x) = 2 pi (c + 0.5) / width - pi, row r (from the top) at elevation asin(y) =
// pi/2 - pi (r + 0.5) / height: Blender's Environment Texture layout once weir's y up is turned
// to Blender's z up by (x, y, z) -> (x, -z, y).
void writeSkyHdr(const std::string& path, const WaterLook& look, int width);

// Linear RGB radiance of width x height pixels (rows from the top) as a little-endian PFM.
void writeRadiancePfm(const std::string& path, const std::vector<Vec3f>& radiance, int width,
                      int height);

// The camera, image, container, side walls, the look's constants and the radiance of the sun's
// disc, as JSON (keys named as in WaterLook and PinholeCamera). Obstacles and bodies are not
// written: `otherTriangles` counts their triangles.
void writeWaterSceneJson(const std::string& path, const TracingScene& scene, const WaterLook& look,
                         const PinholeCamera& camera, int width, int height, int samples);

}  // namespace weir
