// OpenVDB frames: the level set from weir's surface mesh (tools::meshToLevelSet), the velocity
// grid splatted from the particles, the point data grid, and reading the points back.
#include "io/vdb_file.h"

#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/PointIndexGrid.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <vector>

#include "io/atomic_file.h"
#include "io/field_registry.h"
#include "io/frame_reader.h"
#include "surface/surface.h"

namespace weir {

namespace {

namespace vdb = openvdb;
namespace vdbp = openvdb::points;

void initializeOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { vdb::initialize(); });
}

vdb::Vec3f positionOf(const HostParticles& p, std::size_t i) {
    return {float(p.x[i]), float(p.y[i]), float(p.z[i])};
}

// Mean particle velocity around each voxel centre within `radius`, weighted by
// (1 - r^2 / radius^2)^3: sums of weight * v and of weight on the voxels, then their ratio.
vdb::Vec3fGrid::Ptr velocityGrid(const HostParticles& particles, const vdb::math::Transform& xform,
                                 double radius) {
    vdb::Vec3fGrid::Ptr sums = vdb::Vec3fGrid::create(vdb::Vec3f(0));
    vdb::FloatGrid::Ptr weights = vdb::FloatGrid::create(0);
    sums->setTransform(xform.copy());
    auto sum = sums->getAccessor();
    auto weight = weights->getAccessor();
    const double voxel = xform.voxelSize()[0];
    const double radius2 = radius * radius;
    const int reach = int(std::ceil(radius / voxel));
    for (std::size_t i = 0; i < particles.size(); ++i) {
        const vdb::Vec3d at = xform.worldToIndex(vdb::Vec3d(positionOf(particles, i)));
        const vdb::Coord centre = vdb::Coord::round(at);
        const vdb::Vec3f v(float(particles.vx[i]), float(particles.vy[i]), float(particles.vz[i]));
        for (int dx = -reach; dx <= reach; ++dx) {
            for (int dy = -reach; dy <= reach; ++dy) {
                for (int dz = -reach; dz <= reach; ++dz) {
                    const vdb::Coord ijk = centre.offsetBy(dx, dy, dz);
                    const double r2 = (ijk.asVec3d() - at).lengthSqr() * voxel * voxel;
                    if (r2 >= radius2) {
                        continue;
                    }
                    const double s = 1 - r2 / radius2;
                    const float w = float(s * s * s);
                    sum.setValue(ijk, sum.getValue(ijk) + v * w);
                    weight.setValue(ijk, weight.getValue(ijk) + w);
                }
            }
        }
    }
    for (auto voxelIt = sums->beginValueOn(); voxelIt; ++voxelIt) {
        voxelIt.setValue(*voxelIt / weight.getValue(voxelIt.getCoord()));
    }
    return sums;
}

// Appends attribute `name` of type T to the points, from values[i] for particle i.
template <class T>
void addPointAttribute(vdbp::PointDataGrid& points, const vdb::tools::PointIndexGrid& index,
                       const std::string& name, const std::vector<T>& values) {
    vdbp::appendAttribute<T>(points.tree(), name);
    const vdbp::PointAttributeVector<T> wrapper(values);
    vdbp::populateAttribute<vdbp::PointDataTree, vdb::tools::PointIndexTree,
                            vdbp::PointAttributeVector<T>>(points.tree(), index.tree(), name,
                                                           wrapper);
}

// The particles as a point data grid with voxels of 2 d (about 8 particles a voxel at rest).
vdbp::PointDataGrid::Ptr pointsGrid(const HostParticles& particles, double spacing) {
    const std::size_t n = particles.size();
    std::vector<vdb::Vec3f> positions(n), velocities(n);
    std::vector<std::int32_t> ids(n);
    std::vector<float> density(n), pressure(n);
    for (std::size_t i = 0; i < n; ++i) {
        positions[i] = positionOf(particles, i);
        velocities[i] = {float(particles.vx[i]), float(particles.vy[i]), float(particles.vz[i])};
        ids[i] = std::int32_t(particles.idOf(i));
        density[i] = float(particles.rho[i]);
        pressure[i] = float(particles.p[i]);
    }
    const vdbp::PointAttributeVector<vdb::Vec3f> positionWrapper(positions);
    const vdb::math::Transform::Ptr xform =
        vdb::math::Transform::createLinearTransform(2 * spacing);
    const vdb::tools::PointIndexGrid::Ptr index =
        vdb::tools::createPointIndexGrid<vdb::tools::PointIndexGrid>(positionWrapper, *xform);
    vdbp::PointDataGrid::Ptr points =
        vdbp::createPointDataGrid<vdbp::NullCodec, vdbp::PointDataGrid>(*index, positionWrapper,
                                                                        *xform);
    addPointAttribute(*points, *index, "v", velocities);
    addPointAttribute(*points, *index, kParticleIdName, ids);
    addPointAttribute(*points, *index, "density", density);
    addPointAttribute(*points, *index, "pressure", pressure);
    points->setName(kVdbPointsGrid);
    return points;
}

// OpenVDB's message with runs of white space as one space, at most 200 characters: a corrupt
// file's messages quote what it read, e.g. a type name of a million spaces.
std::string shortened(const std::string& what) {
    std::string text;
    for (char c : what) {
        const bool space = c == ' ' || c == '\t' || c == '\n' || c == '\r';
        if (!(space && !text.empty() && text.back() == ' ')) {
            text += space ? ' ' : c;
        }
        if (text.size() >= 200) {
            return text + "...";
        }
    }
    return text;
}

[[noreturn]] void unreadable(const std::string& path, const std::string& what) {
    throw IoError("cannot read '" + path + "': " + what);
}

// The handle of a point attribute of type T, or an IoError naming the attribute.
template <class T>
vdbp::AttributeHandle<T> attributeOf(const vdbp::PointDataTree::LeafNodeType& leaf,
                                     const std::string& name, const std::string& path) {
    const std::size_t at = leaf.attributeSet().find(name);
    if (at == vdbp::AttributeSet::INVALID_POS) {
        unreadable(path, "the grid '" + std::string(kVdbPointsGrid) + "' has no point attribute '" +
                             name + "'");
    }
    const vdbp::AttributeArray& array = leaf.constAttributeArray(at);
    if (!array.hasValueType<T>()) {
        unreadable(path, "point attribute '" + name + "' has type " + array.valueType() +
                             ", expected " + vdb::typeNameAsString<T>());
    }
    return vdbp::AttributeHandle<T>(array);
}

HostParticles readPoints(const vdbp::PointDataGrid& grid, const std::string& path,
                         std::vector<std::int64_t>& ids) {
    const vdb::Index64 count = vdbp::pointCount(grid.tree());
    HostParticles particles;
    particles.resize(std::size_t(count));
    ids.resize(std::size_t(count));
    std::size_t row = 0;
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        auto position = attributeOf<vdb::Vec3f>(*leaf, "P", path);
        auto velocity = attributeOf<vdb::Vec3f>(*leaf, "v", path);
        auto id = attributeOf<std::int32_t>(*leaf, kParticleIdName, path);
        auto density = attributeOf<float>(*leaf, "density", path);
        auto pressure = attributeOf<float>(*leaf, "pressure", path);
        for (auto index = leaf->beginIndexOn(); index; ++index) {
            if (row >= count) {
                unreadable(path, "more points than its count " + std::to_string(count));
            }
            const vdb::Vec3d world = grid.transform().indexToWorld(
                vdb::Vec3d(position.get(*index)) + index.getCoord().asVec3d());
            const vdb::Vec3f v = velocity.get(*index);
            particles.x[row] = Real(world.x());
            particles.y[row] = Real(world.y());
            particles.z[row] = Real(world.z());
            particles.vx[row] = Real(v.x());
            particles.vy[row] = Real(v.y());
            particles.vz[row] = Real(v.z());
            particles.rho[row] = Real(density.get(*index));
            particles.p[row] = Real(pressure.get(*index));
            ids[row] = id.get(*index);
            ++row;
        }
    }
    if (row != count) {
        unreadable(path,
                   std::to_string(row) + " points where its count says " + std::to_string(count));
    }
    return particles;
}

}  // namespace

void writeVdbFrame(const std::string& path, const HostParticles& particles,
                   const VdbFrameOptions& options, const TriangleMesh* surface) {
    initializeOpenVdb();
    SurfaceOptions surfaceOptions;
    surfaceOptions.spacing = options.spacing;
    surfaceOptions.cellSize = options.voxelSize;
    TriangleMesh reconstructed;
    double spacing = options.spacing;
    double voxel = options.voxelSize;
    if (surface == nullptr || spacing <= 0 || voxel <= 0) {
        SurfacePlan plan;
        if (surface == nullptr) {
            reconstructed = reconstructSurface(Backend::Cpu, particles, surfaceOptions, &plan);
            surface = &reconstructed;
        } else {
            plan = planSurface(particles, surfaceOptions);
        }
        spacing = plan.spacing;
        voxel = plan.cellSize;
    }

    const vdb::math::Transform::Ptr xform = vdb::math::Transform::createLinearTransform(voxel);
    std::vector<vdb::Vec3s> vertices(surface->positions.size());
    for (std::size_t v = 0; v < vertices.size(); ++v) {
        const Vec3f& p = surface->positions[v];
        vertices[v] = {p.x, p.y, p.z};
    }
    std::vector<vdb::Vec3I> triangles(surface->triangleCount());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        triangles[t] = {surface->indices[3 * t], surface->indices[3 * t + 1],
                        surface->indices[3 * t + 2]};
    }
    vdb::FloatGrid::Ptr level = vdb::tools::meshToLevelSet<vdb::FloatGrid>(
        *xform, vertices, triangles, float(options.halfWidth));
    level->setName(kVdbSurfaceGrid);
    level->setGridClass(vdb::GRID_LEVEL_SET);

    vdb::Vec3fGrid::Ptr velocity = velocityGrid(particles, *xform, spacing);
    velocity->setName(kVdbVelocityGrid);

    vdb::GridPtrVec grids = {level, velocity, pointsGrid(particles, spacing)};
    vdb::MetaMap metadata;
    metadata.insertMeta("time", vdb::DoubleMetadata(options.time));
    metadata.insertMeta("creator", vdb::StringMetadata("weir"));
    metadata.insertMeta("particle_spacing", vdb::DoubleMetadata(spacing));
    // The rigid bodies' poses (issue 18), as frames.json has them: body_K_position (centre of
    // mass, m), body_K_orientation (quaternion x, y, z, w), body_K_velocity,
    // body_K_angular_velocity.
    metadata.insertMeta("body_count", vdb::Int32Metadata(int(particles.bodies.size())));
    for (std::size_t k = 0; k < particles.bodies.size(); ++k) {
        const BodyPose& b = particles.bodies[k];
        const std::string name = "body_" + std::to_string(k) + "_";
        auto vec3 = [](const Vec3d& v) { return vdb::Vec3DMetadata(vdb::Vec3d(v.x, v.y, v.z)); };
        metadata.insertMeta(name + "position", vec3(b.position));
        metadata.insertMeta(name + "orientation",
                            vdb::Vec4DMetadata(vdb::Vec4d(b.orientation[0], b.orientation[1],
                                                          b.orientation[2], b.orientation[3])));
        metadata.insertMeta(name + "velocity", vec3(b.velocity));
        metadata.insertMeta(name + "angular_velocity", vec3(b.angularVelocity));
    }
    writeFileAtomicallyByName(path, [&](const std::string& tmpPath) {
        try {
            vdb::io::File file(tmpPath);
            file.write(grids, metadata);
            file.close();
        } catch (const vdb::Exception& e) {
            throw IoError("cannot write '" + path + "': OpenVDB: " + e.what());
        }
    });
}

namespace {

// The bodies' poses from the file's metadata (none when body_count is absent: a frame of a
// scene without bodies, or from before they were written).
std::vector<BodyPose> readBodyPoses(const vdb::MetaMap& metadata, const std::string& path) {
    std::vector<BodyPose> bodies;
    const auto count = metadata.getMetadata<vdb::Int32Metadata>("body_count");
    if (!count) {
        return bodies;
    }
    if (count->value() < 0 || count->value() > 4096) {
        unreadable(path,
                   "body_count is " + std::to_string(count->value()) + ", must be within 0..4096");
    }
    for (int k = 0; k < count->value(); ++k) {
        const std::string name = "body_" + std::to_string(k) + "_";
        auto vec3 = [&](const std::string& key) {
            const auto v = metadata.getMetadata<vdb::Vec3DMetadata>(name + key);
            if (!v) {
                unreadable(path, "body_count is " + std::to_string(count->value()) +
                                     " but the metadata " + name + key + " is missing");
            }
            return Vec3d(v->value().x(), v->value().y(), v->value().z());
        };
        BodyPose pose;
        pose.position = vec3("position");
        pose.velocity = vec3("velocity");
        pose.angularVelocity = vec3("angular_velocity");
        const auto q = metadata.getMetadata<vdb::Vec4DMetadata>(name + "orientation");
        if (!q) {
            unreadable(path, "body_count is " + std::to_string(count->value()) +
                                 " but the metadata " + name + "orientation is missing");
        }
        for (int c = 0; c < 4; ++c) {
            pose.orientation[c] = q->value()[c];
        }
        bodies.push_back(pose);
    }
    return bodies;
}

HostParticles readVdbInProcess(const std::string& path, double* time) {
    std::vector<std::int64_t> ids;
    HostParticles particles;
    std::vector<BodyPose> bodies;
    try {
        vdb::io::File file(path);
        file.open(false);  // read grids whole, not mapped: a file changed later cannot hurt
        if (!file.hasGrid(kVdbPointsGrid)) {
            std::string names;
            for (auto name = file.beginName(); name != file.endName(); ++name) {
                names += (names.empty() ? "" : ", ") + name.gridName();
            }
            unreadable(path, "no grid '" + std::string(kVdbPointsGrid) + "' (it holds " +
                                 (names.empty() ? std::string("no grids") : names) + ")");
        }
        const vdb::GridBase::Ptr base = file.readGrid(kVdbPointsGrid);
        const auto grid = vdb::gridPtrCast<vdbp::PointDataGrid>(base);
        if (!grid) {
            unreadable(path, "grid '" + std::string(kVdbPointsGrid) + "' is a " + base->type() +
                                 ", not a point data grid");
        }
        particles = readPoints(*grid, path, ids);
        const vdb::MetaMap::Ptr metadata = file.getMetadata();
        if (time != nullptr) {
            const auto stored = metadata->getMetadata<vdb::DoubleMetadata>("time");
            *time = stored ? stored->value() : 0.0;
        }
        bodies = readBodyPoses(*metadata, path);
        file.close();
    } catch (const IoError&) {
        throw;
    } catch (const std::exception& e) {
        // OpenVDB's own errors (not a VDB, truncated, bad compression) and allocation failures.
        unreadable(path, "not a readable OpenVDB file (" + shortened(e.what()) + ")");
    }
    orderParticlesById(particles, ids, path);
    particles.bodies = std::move(bodies);
    return particles;
}

// How long, and how much more memory than the file's size, a reading may take.
constexpr unsigned kReadSeconds = 300;
constexpr std::uint64_t kReadBytesPerFileByte = 64;
constexpr std::uint64_t kReadBytesAtLeast = std::uint64_t(1) << 30;

// OpenVDB trusts the lengths and counts it reads: a truncated or corrupt file can make it
// allocate without bound (a truncated frame asked for gigabytes, and the OOM killer ended weir
// without a word). So a child process reads the file first, its address space bounded, and says
// what went wrong; the file is read here only once the child read it whole.
void readInBoundedChild(const std::string& path) {
    std::error_code ec;
    const std::uint64_t fileBytes = std::filesystem::file_size(path, ec);
    if (ec) {
        unreadable(path, "not a readable OpenVDB file (" + ec.message() + ")");
    }
    const std::uint64_t page = std::uint64_t(::sysconf(_SC_PAGESIZE));
    const std::uint64_t physical = std::uint64_t(::sysconf(_SC_PHYS_PAGES)) * page;
    const std::uint64_t budget =
        std::min(physical / 2, std::max(kReadBytesAtLeast, kReadBytesPerFileByte * fileBytes));
    int fds[2];
    if (::pipe(fds) != 0) {
        return;  // no child to be had: read in this process, unguarded
    }
    const pid_t child = ::fork();
    if (child < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        return;
    }
    if (child == 0) {
        ::close(fds[0]);
        // Bound the address space to what it is now plus the budget, be the OOM killer's first
        // choice if it comes to that, and stop after kReadSeconds.
        std::uint64_t pagesNow = 0;
        if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
            if (std::fscanf(statm, "%lu", &pagesNow) != 1) {
                pagesNow = 0;
            }
            std::fclose(statm);
        }
        if (pagesNow > 0) {
            const rlimit limit{rlim_t(pagesNow * page + budget), rlim_t(pagesNow * page + budget)};
            ::setrlimit(RLIMIT_AS, &limit);
        }
        if (std::FILE* oom = std::fopen("/proc/self/oom_score_adj", "w")) {
            std::fputs("1000", oom);
            std::fclose(oom);
        }
        ::alarm(kReadSeconds);
        std::string message;
        try {
            readVdbInProcess(path, nullptr);
        } catch (const std::bad_alloc&) {
            message = "cannot read '" + path +
                      "': not a readable OpenVDB file (reading it asked for more than " +
                      std::to_string(budget >> 20) + " MiB: corrupt or truncated)";
        } catch (const std::exception& e) {
            message = e.what();
        } catch (...) {
            message = "cannot read '" + path + "': not a readable OpenVDB file";
        }
        if (!message.empty()) {
            const ssize_t written = ::write(fds[1], message.data(), message.size());
            (void)written;
        }
        ::_exit(message.empty() ? 0 : 1);
    }
    ::close(fds[1]);
    std::string message;
    char buffer[4096];
    for (ssize_t got; (got = ::read(fds[0], buffer, sizeof buffer)) != 0;) {
        if (got < 0) {
            if (errno == EINTR) {
                continue;
            }
            break;
        }
        message.append(buffer, std::size_t(got));
    }
    ::close(fds[0]);
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        return;
    }
    if (WIFEXITED(status) && !message.empty()) {
        throw IoError(message);
    }
    const int signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    unreadable(
        path,
        "not a readable OpenVDB file (" +
            (signal == SIGALRM ? "reading it took more than " + std::to_string(kReadSeconds) + " s"
             : signal == SIGKILL ? std::string("reading it ran out of memory")
                                 : "reading it failed with signal " + std::to_string(signal)) +
            ": corrupt or truncated)");
}

}  // namespace

HostParticles readVdbFrame(const std::string& path, double* time) {
    initializeOpenVdb();
    readInBoundedChild(path);
    return readVdbInProcess(path, time);
}

}  // namespace weir
