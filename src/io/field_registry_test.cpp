// Tests for the particle field registry that drives the exporters.
#include "io/field_registry.h"

#include <gtest/gtest.h>

namespace weir {
namespace {

TEST(FieldRegistry, ListsVelocityDensityPressureOverTheParticleArrays) {
    HostParticles particles;
    const auto fields = particleFields(particles);
    ASSERT_EQ(fields.size(), 3u);
    EXPECT_EQ(fields[0].name, "velocity");
    EXPECT_EQ(fields[0].components, 3);
    EXPECT_EQ(fields[0].componentNames, (std::vector<std::string>{"vx", "vy", "vz"}));
    EXPECT_EQ(fields[0].arrays,
              (std::vector<const std::vector<Real>*>{&particles.vx, &particles.vy, &particles.vz}));
    EXPECT_EQ(fields[1].name, "density");
    EXPECT_EQ(fields[1].components, 1);
    EXPECT_EQ(fields[1].arrays[0], &particles.rho);
    EXPECT_EQ(fields[2].name, "pressure");
    EXPECT_EQ(fields[2].arrays[0], &particles.p);
    for (const auto& field : fields) {
        EXPECT_EQ(field.arrays.size(), std::size_t(field.components));
        EXPECT_EQ(field.componentNames.size(), std::size_t(field.components));
    }
    EXPECT_EQ(mutableParticleFields(particles)[1].arrays[0], &particles.rho);
}

TEST(FieldRegistry, ColumnsArePositionsThenFieldComponents) {
    HostParticles particles;
    EXPECT_EQ(particleColumnNames(),
              (std::vector<std::string>{"x", "y", "z", "vx", "vy", "vz", "density", "pressure"}));
    const auto columns = particleColumns(particles);
    ASSERT_EQ(columns.size(), 8u);
    EXPECT_EQ(columns[0], &particles.x);
    EXPECT_EQ(columns[5], &particles.vz);
    EXPECT_EQ(columns[7], &particles.p);
    EXPECT_EQ(mutableParticleColumns(particles)[6], &particles.rho);
}

}  // namespace
}  // namespace weir
