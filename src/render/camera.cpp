// Orbit camera math.
#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace weir {

namespace {

constexpr double kPi = 3.14159265358979323846;
double radians(double degrees) { return degrees * kPi / 180.0; }

Vec3d normalized(const Vec3d& v) { return v / length(v); }

// Comma-separated finite numbers, exactly `count` of them.
std::vector<double> parseNumbers(const std::string& spec, std::size_t count,
                                 const std::string& flag, const std::string& form) {
    std::vector<double> values;
    std::stringstream in(spec);
    std::string item;
    while (std::getline(in, item, ',')) {
        std::size_t used = 0;
        double value = 0;
        try {
            value = std::stod(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        while (used < item.size() && item[used] == ' ') {
            ++used;
        }
        if (used == 0 || used != item.size() || !std::isfinite(value)) {
            throw std::invalid_argument(flag + " '" + spec + "': '" + item +
                                        "' is not a number; expected " + form);
        }
        values.push_back(value);
    }
    if (values.size() != count) {
        throw std::invalid_argument(flag + " '" + spec + "': expected " + form);
    }
    return values;
}

}  // namespace

Mat4 Mat4::identity() {
    Mat4 r;
    for (int i = 0; i < 4; ++i) {
        r.at(i, i) = 1;
    }
    return r;
}

Mat4 Mat4::operator*(const Mat4& o) const {
    Mat4 r;
    for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 4; ++col) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) {
                sum += double(at(row, k)) * double(o.at(k, col));
            }
            r.at(row, col) = float(sum);
        }
    }
    return r;
}

std::array<double, 4> Mat4::apply(double x, double y, double z, double w) const {
    std::array<double, 4> r{};
    for (int row = 0; row < 4; ++row) {
        r[std::size_t(row)] = at(row, 0) * x + at(row, 1) * y + at(row, 2) * z + at(row, 3) * w;
    }
    return r;
}

Mat4 lookAt(const Vec3d& eye, const Vec3d& target, const Vec3d& up) {
    const Vec3d f = normalized(target - eye);
    const Vec3d s = normalized(cross(f, up));
    const Vec3d u = cross(s, f);
    Mat4 r = Mat4::identity();
    const Vec3d rows[3] = {s, u, -f};
    for (int row = 0; row < 3; ++row) {
        r.at(row, 0) = float(rows[row].x);
        r.at(row, 1) = float(rows[row].y);
        r.at(row, 2) = float(rows[row].z);
        r.at(row, 3) = float(-dot(rows[row], eye));
    }
    return r;
}

Mat4 perspective(double fovYDegrees, double aspect, double nearPlane, double farPlane) {
    const double f = 1.0 / std::tan(radians(fovYDegrees) / 2);
    Mat4 r;
    r.at(0, 0) = float(f / aspect);
    r.at(1, 1) = float(f);
    r.at(2, 2) = float((farPlane + nearPlane) / (nearPlane - farPlane));
    r.at(2, 3) = float(2 * farPlane * nearPlane / (nearPlane - farPlane));
    r.at(3, 2) = -1;
    return r;
}

Mat4 pixelOrtho(int width, int height) {
    Mat4 r = Mat4::identity();
    r.at(0, 0) = 2.0f / float(width);
    r.at(1, 1) = 2.0f / float(height);
    r.at(0, 3) = -1;
    r.at(1, 3) = -1;
    return r;
}

Vec3d OrbitCamera::eye() const {
    const double cp = std::cos(radians(pitch));
    const Vec3d offset{cp * std::sin(radians(yaw)), std::sin(radians(pitch)),
                       cp * std::cos(radians(yaw))};
    return target + offset * distance;
}

Vec3d OrbitCamera::forward() const { return normalized(target - eye()); }
Vec3d OrbitCamera::right() const { return normalized(cross(forward(), Vec3d{0, 1, 0})); }
Vec3d OrbitCamera::up() const { return cross(right(), forward()); }

Mat4 OrbitCamera::view() const { return lookAt(eye(), target, {0, 1, 0}); }

Mat4 OrbitCamera::projection(double aspect) const {
    return perspective(fovY, aspect, distance * 0.01, distance * 20);
}

void OrbitCamera::orbit(double dYawDegrees, double dPitchDegrees) {
    yaw = std::fmod(yaw + dYawDegrees, 360.0);
    pitch = std::clamp(pitch + dPitchDegrees, -89.0, 89.0);
}

void OrbitCamera::pan(double dxFraction, double dyFraction) {
    const double visibleHeight = 2 * distance * std::tan(radians(fovY) / 2);
    target += (right() * dxFraction + up() * dyFraction) * visibleHeight;
}

void OrbitCamera::zoom(double factor) { distance = std::clamp(distance * factor, 1e-4, 1e6); }

OrbitCamera frameBox(const Box& box, double aspect, double yaw, double pitch) {
    OrbitCamera camera;
    camera.yaw = yaw;
    camera.pitch = pitch;
    camera.target = (box.min + box.max) * 0.5;
    const double radius = std::max(0.5 * length(box.max - box.min), 1e-6);
    // The bounding sphere fits the narrower of the two fields of view.
    const double halfY = radians(camera.fovY) / 2;
    const double halfX = std::atan(std::tan(halfY) * aspect);
    camera.distance = radius / std::sin(std::min(halfX, halfY));
    return camera;
}

PixelPoint projectToPixel(const OrbitCamera& camera, const Vec3d& point, int width, int height) {
    const Mat4 viewProjection = camera.projection(double(width) / height) * camera.view();
    const auto clip = viewProjection.apply(point.x, point.y, point.z);
    PixelPoint p;
    p.inFront = clip[3] > 0;
    const double w = clip[3] != 0 ? clip[3] : 1e-30;
    p.x = (clip[0] / w * 0.5 + 0.5) * width;
    p.y = (1 - (clip[1] / w * 0.5 + 0.5)) * height;
    p.depth = clip[2] / w * 0.5 + 0.5;
    return p;
}

double projectedRadius(const OrbitCamera& camera, const Vec3d& point, double radius, int height) {
    const auto viewPoint = camera.view().apply(point.x, point.y, point.z);
    const double focal = 1.0 / std::tan(radians(camera.fovY) / 2);
    return radius * focal * 0.5 * height / std::max(-viewPoint[2], 1e-9);
}

void applyCameraSpec(const std::string& spec, OrbitCamera& camera, const std::string& flag) {
    const std::vector<double> v = parseNumbers(spec, 3, flag, "yaw,pitch,distance");
    if (v[1] <= -90 || v[1] >= 90) {
        throw std::invalid_argument(flag + " '" + spec + "': pitch " + std::to_string(v[1]) +
                                    " must be in (-90, 90) degrees");
    }
    if (v[2] <= 0) {
        throw std::invalid_argument(flag + " '" + spec + "': distance " + std::to_string(v[2]) +
                                    " must be > 0 metres");
    }
    camera.yaw = v[0];
    camera.pitch = v[1];
    camera.distance = v[2];
}

Vec3d parsePoint(const std::string& spec, const std::string& flag) {
    const std::vector<double> v = parseNumbers(spec, 3, flag, "x,y,z");
    return {v[0], v[1], v[2]};
}

OrbitCamera commandLineCamera(const Box& box, double aspect, const std::string& cameraSpec,
                              const std::string& targetSpec) {
    OrbitCamera camera = frameBox(box, aspect);
    if (!cameraSpec.empty()) {
        applyCameraSpec(cameraSpec, camera, "--camera");
    }
    if (!targetSpec.empty()) {
        camera.target = parsePoint(targetSpec, "--target");
    }
    return camera;
}

}  // namespace weir
