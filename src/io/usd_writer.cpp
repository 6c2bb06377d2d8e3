// writeUsdStage: one pass over the frames into per-attribute temporaries, then the stage's text
// with each attribute's samples copied in.
#include "io/usd_writer.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <ostream>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/frame_index.h"
#include "io/io_util.h"
#include "io/mesh_reader.h"
#include "surface/point_velocity.h"

namespace weir {

namespace {

// The time samples of one attribute, kept in a temporary file beside the stage until the stage
// is put together (named NAME.tmp.PID.N.ATTRIBUTE: removeStaleTemporaries knows the pattern).
class Spool {
   public:
    Spool(const std::string& stagePath, const std::string& attribute) {
        static std::atomic<unsigned> counter{0};
        path_ = stagePath + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++) +
                "." + attribute;
        out_.open(path_, std::ios::binary | std::ios::trunc);
        if (!out_) {
            throw IoError("cannot write '" + stagePath + "': cannot create temporary '" + path_ +
                          "'");
        }
    }
    ~Spool() {
        out_.close();
        std::error_code ignored;
        std::filesystem::remove(path_, ignored);
    }
    Spool(const Spool&) = delete;
    Spool& operator=(const Spool&) = delete;

    void append(const std::string& text) {
        out_ << text;
        bytes_ += text.size();
    }
    // Copies the samples into the stage; IoError if the temporary could not be written or read.
    void copyTo(std::ostream& stage, const std::string& stagePath) {
        out_.flush();
        if (!out_) {
            throw IoError("cannot write '" + stagePath + "': writing temporary '" + path_ +
                          "' failed");
        }
        if (bytes_ == 0) {
            return;
        }
        std::ifstream in(path_, std::ios::binary);
        stage << in.rdbuf();
        if (!in || !stage) {
            throw IoError("cannot write '" + stagePath + "': copying temporary '" + path_ +
                          "' failed");
        }
    }

   private:
    std::string path_;
    std::ofstream out_;
    std::size_t bytes_ = 0;
};

// The shortest text of the float; NaN as "nan" whatever its sign (USD's parser refuses "-nan").
std::string number(double value) {
    return std::isnan(value) ? std::string("nan") : numberText(float(value));
}

std::string vec(double x, double y, double z) {
    std::string text(1, '(');  // appended piece by piece: GCC 12 warns on "(" + string (-Wrestrict)
    text.append(number(x)).append(", ").append(number(y)).append(", ").append(number(z));
    return text.append(")");
}

std::string quotedText(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
        }
        out += c == '\n' ? ' ' : c;
    }
    return out + "\"";
}

// "a, b, ...": items item(i), i < count.
template <class Item>
std::string joined(std::size_t count, Item item) {
    std::string text;
    for (std::size_t i = 0; i < count; ++i) {
        if (i > 0) {
            text += ", ";
        }
        text += item(i);
    }
    return text;
}

// "            N: [a, b, ...],\n": one time sample of an array attribute.
template <class Item>
std::string sample(int timeCode, std::size_t count, Item item) {
    return "            " + std::to_string(timeCode) + ": [" + joined(count, item) + "],\n";
}

// The box around point(i), i < count, as a sample of a USD extent.
template <class Point>
std::string extentSample(int timeCode, std::size_t count, Point point) {
    Vec3d lo(0, 0, 0), hi(0, 0, 0);
    for (std::size_t i = 0; i < count; ++i) {
        const Vec3d p = point(i);
        for (int a = 0; a < 3; ++a) {
            lo[a] = i == 0 ? p[a] : std::min(lo[a], p[a]);
            hi[a] = i == 0 ? p[a] : std::max(hi[a], p[a]);
        }
    }
    return "            " + std::to_string(timeCode) + ": [" + vec(lo.x, lo.y, lo.z) + ", " +
           vec(hi.x, hi.y, hi.z) + "],\n";
}

// A triangle mesh as a UsdGeomMesh named `name`, its points moved by -origin.
void writeMesh(std::ostream& out, const std::string& indent, const std::string& name,
               const MeshObstacle& m, const Vec3d& origin) {
    out << indent << "def Mesh \"" << name << "\"\n"
        << indent << "{\n"
        << indent << "    int[] faceVertexCounts = ["
        << joined(m.triangles.size(), [](std::size_t) { return std::string("3"); }) << "]\n"
        << indent << "    int[] faceVertexIndices = ["
        << joined(m.triangles.size(),
                  [&](std::size_t t) {
                      return std::to_string(m.triangles[t][0]) + ", " +
                             std::to_string(m.triangles[t][1]) + ", " +
                             std::to_string(m.triangles[t][2]);
                  })
        << "]\n"
        << indent << "    point3f[] points = ["
        << joined(m.vertices.size(),
                  [&](std::size_t v) {
                      const Vec3d p = m.vertices[v] - origin;
                      return vec(p.x, p.y, p.z);
                  })
        << "]\n"
        << indent << "    uniform token subdivisionScheme = \"none\"\n"
        << indent << "}\n";
}

// An attribute's declaration and its samples: "TYPE NAME.timeSamples = {" ... "}".
void writeSampled(std::ostream& out, const std::string& indent, const std::string& declaration,
                  Spool& spool, const std::string& stagePath) {
    out << indent << declaration << ".timeSamples = {\n";
    spool.copyTo(out, stagePath);
    out << indent << "}\n";
}

void writeCube(std::ostream& out, const std::string& indent, const std::string& name,
               const Box& box, bool guide) {
    const Vec3d centre = (box.min + box.max) * 0.5;
    const Vec3d size = box.max - box.min;
    out << indent << "def Cube \"" << name << "\"\n"
        << indent << "{\n"
        << indent << "    float3[] extent = [(-0.5, -0.5, -0.5), (0.5, 0.5, 0.5)]\n";
    if (guide) {
        out << indent << "    uniform token purpose = \"guide\"\n";
    }
    out << indent << "    double size = 1\n"
        << indent << "    double3 xformOp:translate = " << vec(centre.x, centre.y, centre.z) << "\n"
        << indent << "    float3 xformOp:scale = " << vec(size.x, size.y, size.z) << "\n"
        << indent
        << "    uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:scale\"]\n"
        << indent << "}\n";
}

void writeObstacles(std::ostream& out, const Scene& scene) {
    writeCube(out, "    ", "container", scene.container, true);
    if (scene.obstacleBoxes.empty() && scene.obstacleSpheres.empty() &&
        scene.obstacleMeshes.empty()) {
        return;
    }
    out << "\n    def Xform \"obstacles\"\n    {\n";
    for (std::size_t k = 0; k < scene.obstacleBoxes.size(); ++k) {
        writeCube(out, "        ", "box_" + std::to_string(k), scene.obstacleBoxes[k], false);
    }
    for (std::size_t k = 0; k < scene.obstacleSpheres.size(); ++k) {
        const SphereShape& s = scene.obstacleSpheres[k];
        out << "        def Sphere \"sphere_" << k << "\"\n        {\n"
            << "            float3[] extent = [" << vec(-s.radius, -s.radius, -s.radius) << ", "
            << vec(s.radius, s.radius, s.radius) << "]\n"
            << "            double radius = " << numberText(s.radius) << "\n"
            << "            double3 xformOp:translate = " << vec(s.center.x, s.center.y, s.center.z)
            << "\n"
            << "            uniform token[] xformOpOrder = [\"xformOp:translate\"]\n"
            << "        }\n";
    }
    for (std::size_t k = 0; k < scene.obstacleMeshes.size(); ++k) {
        writeMesh(out, "        ", "mesh_" + std::to_string(k), scene.obstacleMeshes[k], Vec3d());
    }
    out << "    }\n";
}

// The rigid bodies: each an Xform moved by its poses' time samples, holding its shape as it is in
// the body's own frame (centred on the body's centre). Frames without every body's pose (a run
// from before bodies were recorded) give no samples; no frame with them, no bodies.
void writeBodies(std::ostream& out, const Scene& scene, const std::vector<UsdFrame>& frames) {
    const std::size_t count = scene.bodies.size();
    const bool posed = count > 0 && std::any_of(frames.begin(), frames.end(), [&](const auto& f) {
                           return f.bodies.size() == count;
                       });
    if (!posed) {
        return;
    }
    out << "\n    def Xform \"bodies\"\n    {\n";
    for (std::size_t k = 0; k < count; ++k) {
        const BodySpec& body = scene.bodies[k];
        std::string translate, orient;
        for (const UsdFrame& f : frames) {
            if (f.bodies.size() != count) {
                continue;
            }
            const BodyPose& pose = f.bodies[k];
            const std::string at = "                " + std::to_string(f.number) + ": ";
            translate += at + vec(pose.position.x, pose.position.y, pose.position.z) + ",\n";
            orient += at + "(" + number(pose.orientation[3]) + ", " + number(pose.orientation[0]) +
                      ", " + number(pose.orientation[1]) + ", " + number(pose.orientation[2]) +
                      "),\n";
        }
        out << "        def Xform \"body_" << k << "\"\n        {\n"
            << "            double3 xformOp:translate.timeSamples = {\n"
            << translate << "            }\n"
            << "            quatf xformOp:orient.timeSamples = {\n"
            << orient << "            }\n"
            << "            uniform token[] xformOpOrder = [\"xformOp:translate\", "
               "\"xformOp:orient\"]\n";
        if (body.isMesh) {  // about its centre of mass, as the pose is
            writeMesh(out, "            ", "shape", body.mesh, body.centre());
        } else if (body.isSphere) {
            const double r = body.sphere.radius;
            out << "            def Sphere \"shape\"\n            {\n"
                << "                float3[] extent = [" << vec(-r, -r, -r) << ", " << vec(r, r, r)
                << "]\n"
                << "                double radius = " << numberText(r) << "\n"
                << "            }\n";
        } else {
            const Vec3d size = body.box.max - body.box.min;
            out << "            def Cube \"shape\"\n            {\n"
                << "                float3[] extent = [(-0.5, -0.5, -0.5), (0.5, 0.5, 0.5)]\n"
                << "                double size = 1\n"
                << "                float3 xformOp:scale = " << vec(size.x, size.y, size.z) << "\n"
                << "                uniform token[] xformOpOrder = [\"xformOp:scale\"]\n"
                << "            }\n";
        }
        out << "        }\n";
    }
    out << "    }\n";
}

}  // namespace

void writeUsdStage(const std::string& path, const std::vector<UsdFrame>& frames,
                   const UsdStageOptions& options) {
    if (frames.empty()) {
        throw std::invalid_argument("cannot write '" + path + "': no frames");
    }
    if (!(options.framesPerSecond > 0) || !std::isfinite(options.framesPerSecond)) {
        throw std::invalid_argument("cannot write '" + path + "': frames per second is " +
                                    numberText(options.framesPerSecond) + ", must be > 0");
    }
    if (!(options.spacing > 0) || !std::isfinite(options.spacing)) {
        throw std::invalid_argument("cannot write '" + path + "': particle spacing is " +
                                    numberText(options.spacing) + ", must be > 0");
    }
    const bool meshes = std::all_of(frames.begin(), frames.end(),
                                    [](const UsdFrame& f) { return !f.meshPath.empty(); });

    // Particles.
    Spool ids(path, "ids"), points(path, "points"), velocities(path, "velocities"),
        extent(path, "extent"), density(path, "density"), pressure(path, "pressure");
    // Surface.
    std::unique_ptr<Spool> meshPoints, meshNormals, meshVelocities, meshCounts, meshIndices,
        meshExtent;
    if (meshes) {
        meshPoints = std::make_unique<Spool>(path, "mesh_points");
        meshNormals = std::make_unique<Spool>(path, "mesh_normals");
        meshVelocities = std::make_unique<Spool>(path, "mesh_velocities");
        meshCounts = std::make_unique<Spool>(path, "mesh_counts");
        meshIndices = std::make_unique<Spool>(path, "mesh_indices");
        meshExtent = std::make_unique<Spool>(path, "mesh_extent");
    }
    int first = frames.front().number, last = first;
    for (const UsdFrame& frame : frames) {
        first = std::min(first, frame.number);
        last = std::max(last, frame.number);
        const int t = frame.number;
        const HostParticles p = readFrameFile(frame.particlesPath);
        const std::size_t n = p.size();
        ids.append(sample(t, n, [&p](std::size_t i) { return std::to_string(p.idOf(i)); }));
        points.append(sample(t, n, [&](std::size_t i) { return vec(p.x[i], p.y[i], p.z[i]); }));
        velocities.append(
            sample(t, n, [&](std::size_t i) { return vec(p.vx[i], p.vy[i], p.vz[i]); }));
        density.append(sample(t, n, [&](std::size_t i) { return number(p.rho[i]); }));
        pressure.append(sample(t, n, [&](std::size_t i) { return number(p.p[i]); }));
        extent.append(
            extentSample(t, n, [&](std::size_t i) { return Vec3d(p.x[i], p.y[i], p.z[i]); }));
        if (!meshes) {
            continue;
        }
        const TriangleMesh mesh = readMesh(frame.meshPath);
        const std::vector<Vec3f> meshVelocity =
            particleVelocityAt(p, mesh.positions, 2 * options.spacing);
        const auto& x = mesh.positions;
        meshPoints->append(
            sample(t, x.size(), [&](std::size_t v) { return vec(x[v].x, x[v].y, x[v].z); }));
        const auto& nrm = mesh.normals;
        meshNormals->append(sample(
            t, nrm.size(), [&](std::size_t v) { return vec(nrm[v].x, nrm[v].y, nrm[v].z); }));
        meshVelocities->append(sample(t, meshVelocity.size(), [&](std::size_t v) {
            return vec(meshVelocity[v].x, meshVelocity[v].y, meshVelocity[v].z);
        }));
        meshCounts->append(
            sample(t, mesh.triangleCount(), [](std::size_t) { return std::string("3"); }));
        meshIndices->append(sample(t, mesh.indices.size(),
                                   [&](std::size_t k) { return std::to_string(mesh.indices[k]); }));
        meshExtent->append(extentSample(
            t, x.size(), [&](std::size_t v) { return Vec3d(x[v].x, x[v].y, x[v].z); }));
    }

    writeFileAtomically(path, [&](std::ostream& out) {
        const std::string fps = numberText(options.framesPerSecond);
        out << "#usda 1.0\n(\n    defaultPrim = \"weir\"\n"
            << "    doc = " << quotedText(options.doc) << "\n"
            << "    endTimeCode = " << last << "\n"
            << "    framesPerSecond = " << fps << "\n"
            << "    metersPerUnit = 1\n"
            << "    startTimeCode = " << first << "\n"
            << "    timeCodesPerSecond = " << fps << "\n"
            << "    upAxis = \"Y\"\n)\n\n"
            << "def Xform \"weir\"\n{\n"
            << "    def Points \"particles\"\n    {\n";
        const std::string in = "        ";
        writeSampled(out, in, "float3[] extent", extent, path);
        writeSampled(out, in, "int64[] ids", ids, path);
        writeSampled(out, in, "point3f[] points", points, path);
        out << in << "float[] primvars:density (\n"
            << in << "    interpolation = \"vertex\"\n"
            << in << ")\n";
        writeSampled(out, in, "float[] primvars:density", density, path);
        out << in << "float[] primvars:pressure (\n"
            << in << "    interpolation = \"vertex\"\n"
            << in << ")\n";
        writeSampled(out, in, "float[] primvars:pressure", pressure, path);
        writeSampled(out, in, "vector3f[] velocities", velocities, path);
        out << in << "float[] widths = [" << numberText(float(options.spacing)) << "] (\n"
            << in << "    interpolation = \"constant\"\n"
            << in << ")\n    }\n";
        if (meshes) {
            out << "\n    def Mesh \"surface\"\n    {\n";
            writeSampled(out, in, "float3[] extent", *meshExtent, path);
            writeSampled(out, in, "int[] faceVertexCounts", *meshCounts, path);
            writeSampled(out, in, "int[] faceVertexIndices", *meshIndices, path);
            out << in << "normal3f[] normals (\n"
                << in << "    interpolation = \"vertex\"\n"
                << in << ")\n";
            writeSampled(out, in, "normal3f[] normals", *meshNormals, path);
            writeSampled(out, in, "point3f[] points", *meshPoints, path);
            out << in << "uniform token subdivisionScheme = \"none\"\n";
            writeSampled(out, in, "vector3f[] velocities", *meshVelocities, path);
            out << "    }\n";
        }
        if (options.scene != nullptr) {
            out << "\n";
            writeObstacles(out, *options.scene);
            writeBodies(out, *options.scene, frames);
        }
        out << "}\n";
    });
}

}  // namespace weir
