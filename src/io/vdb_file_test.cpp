// Tests for OpenVDB frames, read back through OpenVDB's own C++ API: the level set is a signed
// distance of the right sign and size, the velocity grid averages the particles' velocities, the
// point grid holds every particle's attributes; damaged files are refused naming the file.
#include "io/vdb_file.h"

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/PointIndexGrid.h>

#include <cmath>
#include <string>
#include <vector>

#include "io/io_test_support.h"
#include "surface/surface.h"

namespace weir {
namespace {

using test::TempDir;

constexpr double kSpacing = 0.02;

// A 10 x 10 x 10 lattice block at spacing d from (0.01, 0.01, 0.01): the fluid fills
// [0, 0.2]^3. Velocity (x, 1, 0) m/s, density 1000 + i, pressure 2 i.
HostParticles block() {
    HostParticles particles;
    for (int i = 0; i < 10; ++i) {
        for (int j = 0; j < 10; ++j) {
            for (int k = 0; k < 10; ++k) {
                const double x = (i + 0.5) * kSpacing, y = (j + 0.5) * kSpacing,
                             z = (k + 0.5) * kSpacing;
                particles.push({x, y, z}, {x, 1, 0});
            }
        }
    }
    for (std::size_t i = 0; i < particles.size(); ++i) {
        particles.rho[i] = Real(1000 + double(i));
        particles.p[i] = Real(2 * double(i));
    }
    return particles;
}

openvdb::GridPtrVecPtr readGrids(const std::string& path) {
    openvdb::initialize();
    openvdb::io::File file(path);
    file.open();
    openvdb::GridPtrVecPtr grids = file.getGrids();
    file.close();
    return grids;
}

template <class Grid>
typename Grid::Ptr gridNamed(const openvdb::GridPtrVecPtr& grids, const std::string& name) {
    for (const openvdb::GridBase::Ptr& grid : *grids) {
        if (grid->getName() == name) {
            return openvdb::gridPtrCast<Grid>(grid);
        }
    }
    return nullptr;
}

// Expects read() to throw an IoError whose message names path and contains `detail`.
void expectUnreadable(const std::string& path, const std::string& detail) {
    try {
        readVdbFrame(path);
        ADD_FAILURE() << "no IoError for " << path;
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("'" + path + "'"), std::string::npos) << message;
        EXPECT_NE(message.find(detail), std::string::npos) << message;
    }
}

TEST(VdbFile, SurfaceIsANarrowBandLevelSetOfTheFluid) {
    TempDir dir;
    writeVdbFrame(dir / "f.vdb", block(), {0.25, kSpacing, 0, 3});
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"f.vdb"});  // no temporary left
    const auto grids = readGrids(dir / "f.vdb");
    ASSERT_EQ(grids->size(), 3u);
    const auto surface = gridNamed<openvdb::FloatGrid>(grids, "surface");
    ASSERT_TRUE(surface);
    EXPECT_EQ(surface->getGridClass(), openvdb::GRID_LEVEL_SET);
    const double voxel = kSpacing / 2;  // the surface lattice's cell by default
    EXPECT_NEAR(surface->voxelSize()[0], voxel, 1e-12);
    EXPECT_NEAR(surface->background(), 3 * voxel, 1e-6);
    openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sample(*surface);
    // The fluid's volume is [0, 0.2]^3; weir's surface lies within a few mm of its faces.
    EXPECT_NEAR(sample.wsSample(openvdb::Vec3d(0.1, 0.1, 0.1)), -3 * voxel, 1e-6);  // deep inside
    EXPECT_NEAR(sample.wsSample(openvdb::Vec3d(0.3, 0.1, 0.1)), 3 * voxel, 1e-6);   // far outside
    for (double x : {0.19, 0.195, 0.2, 0.205, 0.21}) {
        // Across the face x = 0.2 the distance grows by the step in x, within the surface's
        // offset from the face (under 0.4 d).
        const double phi = sample.wsSample(openvdb::Vec3d(x, 0.1, 0.1));
        EXPECT_NEAR(phi, x - 0.2, 0.4 * kSpacing) << x;
    }
    EXPECT_LT(sample.wsSample(openvdb::Vec3d(0.19, 0.1, 0.1)),
              sample.wsSample(openvdb::Vec3d(0.2, 0.1, 0.1)));
    // A set voxel size is used.
    writeVdbFrame(dir / "g.vdb", block(), {0.25, kSpacing, 0.004, 3});
    EXPECT_NEAR(gridNamed<openvdb::FloatGrid>(readGrids(dir / "g.vdb"), "surface")->voxelSize()[0],
                0.004, 1e-12);
}

TEST(VdbFile, VelocityGridAveragesTheParticlesNearEachVoxel) {
    TempDir dir;
    writeVdbFrame(dir / "f.vdb", block(), {0.25, kSpacing, 0, 3});
    const auto velocity = gridNamed<openvdb::Vec3fGrid>(readGrids(dir / "f.vdb"), "velocity");
    ASSERT_TRUE(velocity);
    const auto accessor = velocity->getConstAccessor();
    const auto& xform = velocity->transform();
    // vy is 1 everywhere, vz 0; vx = x is linear, so a symmetric mean inside the block is x.
    for (double x : {0.05, 0.1, 0.15}) {
        const openvdb::Coord ijk = xform.worldToIndexCellCentered(openvdb::Vec3d(x, 0.1, 0.1));
        ASSERT_TRUE(accessor.isValueOn(ijk)) << x;
        const openvdb::Vec3f v = accessor.getValue(ijk);
        const double at = xform.indexToWorld(ijk).x();
        EXPECT_NEAR(v.x(), at, 1e-5) << x;
        EXPECT_NEAR(v.y(), 1, 1e-5);
        EXPECT_NEAR(v.z(), 0, 1e-6);
    }
    // Nothing further than d from every particle.
    EXPECT_FALSE(accessor.isValueOn(xform.worldToIndexCellCentered(openvdb::Vec3d(0.3, 0.1, 0.1))));
}

TEST(VdbFile, PointsHoldPositionVelocityIdDensityAndPressure) {
    TempDir dir;
    const HostParticles particles = block();
    writeVdbFrame(dir / "f.vdb", particles, {0.25, kSpacing, 0, 3});
    openvdb::initialize();
    openvdb::io::File file(dir / "f.vdb");
    file.open();
    const auto time = file.getMetadata()->getMetadata<openvdb::DoubleMetadata>("time");
    ASSERT_TRUE(time);
    EXPECT_EQ(time->value(), 0.25);
    const auto points =
        openvdb::gridPtrCast<openvdb::points::PointDataGrid>(file.readGrid("points"));
    file.close();
    ASSERT_TRUE(points);
    EXPECT_EQ(openvdb::points::pointCount(points->tree()), particles.size());
    std::vector<int> seen(particles.size(), 0);
    for (auto leaf = points->tree().cbeginLeaf(); leaf; ++leaf) {
        openvdb::points::AttributeHandle<openvdb::Vec3f> position(leaf->constAttributeArray("P"));
        openvdb::points::AttributeHandle<openvdb::Vec3f> v(leaf->constAttributeArray("v"));
        openvdb::points::AttributeHandle<std::int32_t> id(leaf->constAttributeArray("id"));
        openvdb::points::AttributeHandle<float> density(leaf->constAttributeArray("density"));
        openvdb::points::AttributeHandle<float> pressure(leaf->constAttributeArray("pressure"));
        for (auto index = leaf->beginIndexOn(); index; ++index) {
            const int i = id.get(*index);
            ASSERT_GE(i, 0);
            ASSERT_LT(std::size_t(i), particles.size());
            ++seen[std::size_t(i)];
            const openvdb::Vec3d world = points->transform().indexToWorld(
                openvdb::Vec3d(position.get(*index)) + index.getCoord().asVec3d());
            EXPECT_NEAR(world.x(), particles.x[i], 1e-6);
            EXPECT_NEAR(world.y(), particles.y[i], 1e-6);
            EXPECT_NEAR(world.z(), particles.z[i], 1e-6);
            EXPECT_EQ(v.get(*index), openvdb::Vec3f(float(particles.vx[i]), 1, 0));
            EXPECT_EQ(density.get(*index), float(particles.rho[i]));
            EXPECT_EQ(pressure.get(*index), float(particles.p[i]));
        }
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(particles.size()));
}

TEST(VdbFile, ReadsBackInIdOrder) {
    TempDir dir;
    const HostParticles particles = block();
    writeVdbFrame(dir / "f.vdb", particles, {0.5, kSpacing, 0, 3});
    double time = -1;
    const HostParticles read = readVdbFrame(dir / "f.vdb", &time);
    EXPECT_EQ(time, 0.5);
    ASSERT_EQ(read.size(), particles.size());
    for (std::size_t i = 0; i < particles.size(); ++i) {
        ASSERT_NEAR(read.x[i], particles.x[i], 1e-6) << i;
        ASSERT_NEAR(read.y[i], particles.y[i], 1e-6) << i;
        ASSERT_NEAR(read.z[i], particles.z[i], 1e-6) << i;
        ASSERT_EQ(read.vx[i], particles.vx[i]) << i;
        ASSERT_EQ(read.rho[i], particles.rho[i]) << i;
        ASSERT_EQ(read.p[i], particles.p[i]) << i;
    }
}

// The rigid bodies' poses travel in the file's metadata (issue 18), as frames.json has them.
TEST(VdbFile, BodyPosesTravelInTheMetadata) {
    TempDir dir;
    HostParticles particles = block();
    BodyPose a, b;
    a.position = Vec3d(0.1, 0.2, 0.3);
    a.orientation[0] = 0.6;
    a.orientation[3] = 0.8;
    a.velocity = Vec3d(1, -2, 3);
    a.angularVelocity = Vec3d(0, 0, 4);
    b.position = Vec3d(-1, 5, 2);
    particles.bodies = {a, b};
    writeVdbFrame(dir / "f.vdb", particles, {0.5, kSpacing, 0, 3});
    const HostParticles read = readVdbFrame(dir / "f.vdb");
    ASSERT_EQ(read.bodies.size(), 2u);
    EXPECT_EQ(read.bodies[0].position.y, 0.2);
    EXPECT_EQ(read.bodies[0].orientation[0], 0.6);
    EXPECT_EQ(read.bodies[0].orientation[3], 0.8);
    EXPECT_EQ(read.bodies[0].velocity.z, 3);
    EXPECT_EQ(read.bodies[0].angularVelocity.z, 4);
    EXPECT_EQ(read.bodies[1].position.x, -1);
    EXPECT_EQ(read.bodies[1].orientation[3], 1);
    // A frame without bodies reads back without any.
    writeVdbFrame(dir / "g.vdb", block(), {0.5, kSpacing, 0, 3});
    EXPECT_TRUE(readVdbFrame(dir / "g.vdb").bodies.empty());
}

TEST(VdbFile, TruncatedOrForeignFilesAreRefusedNamingTheFile) {
    TempDir dir;
    writeVdbFrame(dir / "f.vdb", block(), {0, kSpacing, 0, 3});
    const std::string bytes = test::fileText(dir / "f.vdb");
    // Cut at 40 lengths across the file (every length would take minutes).
    for (int k = 0; k < 40; ++k) {
        const std::size_t length = bytes.size() * std::size_t(k) / 40;
        SCOPED_TRACE("truncated to " + std::to_string(length) + " of " +
                     std::to_string(bytes.size()));
        test::writeText(dir / "cut.vdb", bytes.substr(0, length));
        expectUnreadable(dir / "cut.vdb", "cannot read");
    }
    test::writeText(dir / "text.vdb", "this is not a VDB file\n");
    expectUnreadable(dir / "text.vdb", "not a readable OpenVDB file");
    expectUnreadable(dir / "missing.vdb", "not a readable OpenVDB file");
}

// Bytes overwritten across the file: whatever OpenVDB makes of them, reading either gives the
// particles or an IoError naming the file, and neither crashes nor exhausts memory (the read is
// tried first in a child process with a bounded address space).
TEST(VdbFile, CorruptBytesGiveParticlesOrAnIoErrorNeverACrash) {
    TempDir dir;
    writeVdbFrame(dir / "f.vdb", block(), {0, kSpacing, 0, 3});
    const std::string bytes = test::fileText(dir / "f.vdb");
    int refused = 0;
    for (int k = 0; k < 60; ++k) {
        std::string corrupt = bytes;
        const std::size_t at = bytes.size() * std::size_t(k) / 60;
        corrupt.replace(at, 4, "\xff\xff\xff\x7f");
        test::writeText(dir / "corrupt.vdb", corrupt);
        try {
            EXPECT_LE(readVdbFrame(dir / "corrupt.vdb").size(), 1000u);
        } catch (const IoError& e) {
            ++refused;
            EXPECT_NE(std::string(e.what()).find(dir / "corrupt.vdb"), std::string::npos)
                << e.what();
        }
    }
    EXPECT_GT(refused, 0);
}

TEST(VdbFile, AVdbWithoutWeirsPointsIsRefusedSayingWhatItHolds) {
    TempDir dir;
    openvdb::initialize();
    openvdb::FloatGrid::Ptr density = openvdb::FloatGrid::create(0);
    density->setName("density");
    density->tree().setValue(openvdb::Coord(1, 2, 3), 1.0f);
    openvdb::io::File(dir / "smoke.vdb").write({density});
    expectUnreadable(dir / "smoke.vdb", "no grid 'points' (it holds density)");

    // Points with positions only (as another tool may write): the missing attribute is named.
    std::vector<openvdb::Vec3f> positions = {{0, 0, 0}, {1, 0, 0}};
    const openvdb::points::PointAttributeVector<openvdb::Vec3f> wrapper(positions);
    const auto xform = openvdb::math::Transform::createLinearTransform(0.5);
    const auto index =
        openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(wrapper, *xform);
    auto points = openvdb::points::createPointDataGrid<openvdb::points::NullCodec,
                                                       openvdb::points::PointDataGrid>(
        *index, wrapper, *xform);
    points->setName("points");
    openvdb::io::File(dir / "bare.vdb").write({points});
    expectUnreadable(dir / "bare.vdb", "has no point attribute 'v'");
}

TEST(VdbFile, UnwritablePathIsAnIoErrorNamingIt) {
    TempDir dir;
    const std::string path = dir / "no/such/dir/f.vdb";
    try {
        writeVdbFrame(path, block(), {0, kSpacing, 0, 3});
        ADD_FAILURE() << "wrote " << path;
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    EXPECT_EQ(dir.entries(), std::vector<std::string>{});
}

}  // namespace
}  // namespace weir
