// Anisotropic surface field (Yu & Turk 2013): the eigen-decomposition it rests on, a thin sheet
// comes out thinner and flatter than with the isotropic field, a ball stays a ball, a box's faces
// stay where the fluid ends; option names.
#include "surface/anisotropy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "surface/mesh_measures.h"
#include "surface/surface.h"
#include "surface/surface_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

TEST(SurfaceAnisotropy, EigenDecompositionRebuildsTheMatrix) {
    SymmetricMatrix3 m;
    m.xx = 4, m.yy = 2, m.zz = 1, m.xy = 0.5, m.xz = -0.3, m.yz = 0.8;
    Real values[3], vectors[3][3];
    symmetricEigen(m, values, vectors);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            double rebuilt = 0, orthogonality = 0;
            for (int k = 0; k < 3; ++k) {
                rebuilt += double(vectors[r][k]) * values[k] * vectors[c][k];
                orthogonality += double(vectors[k][r]) * vectors[k][c];
            }
            EXPECT_NEAR(rebuilt, m.entry(r, c), 1e-5) << r << " " << c;
            EXPECT_NEAR(orthogonality, r == c ? 1.0 : 0.0, 1e-5) << r << " " << c;
        }
    }
    EXPECT_NEAR(double(values[0]) + values[1] + values[2], 7.0, 1e-5);  // the trace
}

// A sheet one particle thick in the xz plane at height y0, its particles jittered up and down by
// up to a fifth of a spacing (a splash's sheet is never a perfect lattice).
HostParticles jitteredSheet(int count, double d, double y0) {
    HostParticles sheet;
    unsigned state = 12345;
    for (int k = 0; k < count; ++k) {
        for (int i = 0; i < count; ++i) {
            state = state * 1664525u + 1013904223u;
            const double jitter = (double(state >> 8) / double(1u << 24) - 0.5) * 0.4 * d;
            sheet.push(Vec3d(i * d, y0 + jitter, k * d), Vec3d());
        }
    }
    return sheet;
}

struct SheetShape {
    double thickness = 0;  // mean height of the upper vertices minus that of the lower ones
    double roughness = 0;  // RMS of the upper vertices' heights about their mean
    std::size_t vertices = 0;
};

// Over the sheet's middle half, away from its rim.
SheetShape sheetShape(const TriangleMesh& mesh, double lo, double hi, double y0) {
    double upSum = 0, upSum2 = 0, downSum = 0;
    std::size_t up = 0, down = 0;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const Vec3d p(mesh.positions[v]);
        if (p.x < lo || p.x > hi || p.z < lo || p.z > hi) {
            continue;
        }
        if (p.y > y0) {
            upSum += p.y;
            upSum2 += p.y * p.y;
            ++up;
        } else {
            downSum += p.y;
            ++down;
        }
    }
    SheetShape s;
    if (up == 0 || down == 0) {
        return s;
    }
    const double upMean = upSum / double(up);
    s.thickness = upMean - downSum / double(down);
    s.roughness = std::sqrt(std::max(0.0, upSum2 / double(up) - upMean * upMean));
    s.vertices = up + down;
    return s;
}

TEST(SurfaceAnisotropy, ThinSheetIsThinnerAndFlatter) {
    const double d = 0.01, y0 = 0.5;
    const int count = 24;
    const HostParticles sheet = jitteredSheet(count, d, y0);
    SurfaceOptions isotropic, anisotropic;
    isotropic.spacing = anisotropic.spacing = d;
    anisotropic.field = SurfaceField::Anisotropic;
    const TriangleMesh a = reconstructSurface(Backend::Cpu, sheet, isotropic);
    const TriangleMesh b = reconstructSurface(Backend::Cpu, sheet, anisotropic);
    const double lo = 0.25 * count * d, hi = 0.75 * count * d;
    const SheetShape iso = sheetShape(a, lo, hi, y0), aniso = sheetShape(b, lo, hi, y0);
    std::printf(
        "sheet one particle thick, jittered +-0.2 d: isotropic %.3f d thick, roughness %.3f d; "
        "anisotropic %.3f d thick, roughness %.3f d\n",
        iso.thickness / d, iso.roughness / d, aniso.thickness / d, aniso.roughness / d);
    ASSERT_GT(iso.vertices, 100u);
    ASSERT_GT(aniso.vertices, 100u);
    EXPECT_TRUE(measureMesh(b).closed());
    EXPECT_EQ(measureMesh(b).components, 1u);  // one sheet, not beads
    EXPECT_LT(aniso.thickness, 0.8 * iso.thickness);
    EXPECT_GT(aniso.thickness, 0.2 * d);  // still a sheet
    EXPECT_LT(aniso.roughness, 0.9 * iso.roughness);
}

TEST(SurfaceAnisotropy, BallStaysABall) {
    const double d = 0.01, radius = 0.1;
    const Vec3d centre(0.4, 1.2, -0.3);
    const HostParticles ball = latticeBall(centre, radius, d);
    SurfaceOptions options;
    options.field = SurfaceField::Anisotropic;
    SurfacePlan plan;
    const TriangleMesh mesh = reconstructSurface(Backend::Cpu, ball, options, &plan);
    EXPECT_EQ(plan.field, SurfaceField::Anisotropic);
    const MeshMeasures m = measureMesh(mesh);
    ASSERT_GT(mesh.triangleCount(), 1000u);
    EXPECT_TRUE(m.closed());
    EXPECT_EQ(m.components, 1u);
    EXPECT_EQ(m.eulerCharacteristic, 2);
    double sum = 0, worst = 0;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const Vec3d p(mesh.positions[v]);
        const double r = length(p - centre);
        sum += r;
        worst = std::max(worst, std::abs(r - radius));
        ASSERT_GT(dot(Vec3d(mesh.normals[v]), p - centre), 0) << "vertex " << v;
    }
    const double mean = sum / double(mesh.vertexCount());
    std::printf("anisotropic ball of radius %.3f d: mean vertex radius %.3f d, worst off %.3f d\n",
                radius / d, mean / d, worst / d);
    EXPECT_NEAR(mean, radius, 0.04 * radius);
    EXPECT_LT(worst, 0.1 * radius);
}

TEST(SurfaceAnisotropy, BoxFacesStayFlatWhereTheFluidEnds) {
    const double d = 0.02;
    const int counts[3] = {16, 10, 12};
    const Vec3d boxMin(-0.1, 0.05, 0.3);
    const Vec3d size(counts[0] * d, counts[1] * d, counts[2] * d);
    SurfaceOptions options;
    options.field = SurfaceField::Anisotropic;
    const TriangleMesh mesh =
        reconstructSurface(Backend::Cpu, latticeBox(boxMin, counts, d), options);
    const MeshMeasures m = measureMesh(mesh);
    EXPECT_TRUE(m.closed());
    EXPECT_EQ(m.eulerCharacteristic, 2);
    const Vec3d centre = boxMin + size * 0.5;
    std::size_t onTop = 0;
    double low = 1e9, high = -1e9;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const Vec3d p(mesh.positions[v]);
        if (std::abs(p.x - centre.x) < 0.25 * size.x && std::abs(p.z - centre.z) < 0.25 * size.z &&
            p.y > centre.y) {
            ++onTop;
            low = std::min(low, p.y);
            high = std::max(high, p.y);
        }
    }
    const double top = boxMin.y + size.y;
    std::printf("anisotropic box: top face from %.3f d to %.3f d off where the fluid ends\n",
                (low - top) / d, (high - top) / d);
    EXPECT_GT(onTop, 20u);
    EXPECT_LT(high - low, 0.02 * d);                 // flat
    EXPECT_NEAR(0.5 * (low + high), top, 0.35 * d);  // smoothed centres pull the face in a little
}

TEST(SurfaceAnisotropy, FieldNamesAndIsoRange) {
    EXPECT_EQ(parseSurfaceField("anisotropic"), SurfaceField::Anisotropic);
    EXPECT_EQ(parseSurfaceField("isotropic"), SurfaceField::Isotropic);
    EXPECT_EQ(std::string(surfaceFieldName(SurfaceField::Anisotropic)), "anisotropic");
    try {
        parseSurfaceField("blobby");
        FAIL() << "an unknown field name was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("'blobby'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("isotropic, anisotropic"), std::string::npos)
            << e.what();
    }
    const int counts[3] = {4, 4, 4};
    const HostParticles box = latticeBox(Vec3d(), counts, 0.01);
    SurfaceOptions options;
    options.field = SurfaceField::Anisotropic;
    options.iso = 0.3;  // in range: inflates
    EXPECT_NO_THROW(planSurface(box, options));
    options.iso = 2;  // beyond every kernel's reach
    EXPECT_THROW(planSurface(box, options), std::invalid_argument);
}

}  // namespace
}  // namespace weir
