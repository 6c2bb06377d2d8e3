// The orbit camera (yaw, pitch, distance around a target) and the 4x4 matrices it makes; the
// same math projects points in tests.
#pragma once

#include <array>
#include <string>

#include "core/vec3.h"
#include "scene/scene.h"

namespace weir {

// Column-major 4x4 matrix, as OpenGL takes it: element (row, col) is m[col * 4 + row].
struct Mat4 {
    std::array<float, 16> m{};

    static Mat4 identity();
    float& at(int row, int col) { return m[std::size_t(col * 4 + row)]; }
    float at(int row, int col) const { return m[std::size_t(col * 4 + row)]; }
    Mat4 operator*(const Mat4& o) const;
    // (x, y, z, w) times this matrix, in double.
    std::array<double, 4> apply(double x, double y, double z, double w = 1.0) const;
};

// Right-handed view matrix looking from eye at target with +y up.
Mat4 lookAt(const Vec3d& eye, const Vec3d& target, const Vec3d& up);
// OpenGL perspective projection (clip z in [-w, w]); fovY in degrees.
Mat4 perspective(double fovYDegrees, double aspect, double nearPlane, double farPlane);
// Pixel-space orthographic projection: (0, 0) is the bottom-left corner, (width, height) the top
// right.
Mat4 pixelOrtho(int width, int height);

struct OrbitCamera {
    double yaw = 25;      // degrees about +y; 0 looks along -z from the +z side
    double pitch = 20;    // degrees above the horizontal, within (-89, 89)
    double distance = 3;  // metres from the target
    Vec3d target{};       // the point orbited and looked at
    double fovY = 40;     // vertical field of view, degrees

    Vec3d eye() const;
    Vec3d forward() const;  // unit, from eye to target
    Vec3d right() const;    // unit, screen right
    Vec3d up() const;       // unit, screen up
    Mat4 view() const;
    // Near and far planes follow the distance, so that zooming keeps depth precision.
    Mat4 projection(double aspect) const;

    void orbit(double dYawDegrees, double dPitchDegrees);
    // Moves the target in the screen plane by fractions of the visible height.
    void pan(double dxFraction, double dyFraction);
    void zoom(double factor);  // distance *= factor
};

// A camera at yaw and pitch whose view holds the whole box (its bounding sphere) at this aspect.
OrbitCamera frameBox(const Box& box, double aspect, double yaw = 25, double pitch = 20);

// Where a point lands in an image of width x height: pixel coordinates with (0, 0) at the top-left
// corner of the top-left pixel (image rows, as PNG stores them), window depth in [0, 1].
struct PixelPoint {
    double x = 0, y = 0, depth = 0;
    bool inFront = false;  // in front of the near plane
};
PixelPoint projectToPixel(const OrbitCamera& camera, const Vec3d& point, int width, int height);
// Radius in pixels of a sphere of `radius` at `point` as the particle shader draws it.
double projectedRadius(const OrbitCamera& camera, const Vec3d& point, double radius, int height);

// Parses "yaw,pitch,distance" (degrees, degrees, metres > 0) into the camera; throws
// std::invalid_argument naming the flag and the value.
void applyCameraSpec(const std::string& spec, OrbitCamera& camera, const std::string& flag);
// Parses "x,y,z" into a point; throws std::invalid_argument naming the flag and the value.
Vec3d parsePoint(const std::string& spec, const std::string& flag);

// The camera of the command line: framed on the box, then --camera and --target (either may be
// empty) applied.
OrbitCamera commandLineCamera(const Box& box, double aspect, const std::string& cameraSpec,
                              const std::string& targetSpec);

}  // namespace weir
