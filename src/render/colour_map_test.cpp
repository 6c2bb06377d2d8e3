// The colour fields come from the field registry: every colourable field of the registry (a
// scalar by its name, a vector by its magnitude) is a colour field, in the registry's order, with
// its unit, its values and a physical range.
#include "render/colour_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "io/field_registry.h"

namespace weir {
namespace {

TEST(ColourFields, AreTheRegistrysColourableFieldsInItsOrder) {
    std::vector<std::string> fromRegistry;
    for (const FieldInfo& field : particleFieldInfo()) {
        if (!field.colourName.empty()) {
            fromRegistry.push_back(field.colourName);
        }
    }
    EXPECT_EQ(colourFieldNames(), fromRegistry);
    EXPECT_EQ(colourFieldNames(), (std::vector<std::string>{"speed", "density", "pressure"}));
    EXPECT_EQ(colourFieldList(), "speed, density, pressure");
    ASSERT_EQ(ColourField::all().size(), fromRegistry.size());
    for (const ColourField field : ColourField::all()) {
        SCOPED_TRACE(field.name());
        EXPECT_EQ(parseColourField(field.name()), field);
        const FieldInfo& info = particleFieldInfo()[field.fieldIndex()];
        EXPECT_EQ(field.unit(), info.unit);
        EXPECT_EQ(field.magnitude(), info.components > 1);
    }
    EXPECT_EQ(std::string(colourFieldUnit(ColourField::Speed)), "m/s");
    EXPECT_EQ(std::string(colourFieldUnit(ColourField::Density)), "kg/m3");
    EXPECT_EQ(std::string(colourFieldName(ColourField::Pressure)), "pressure");
}

TEST(ColourFields, CycleThroughEveryOneAndRefuseUnknownNamesListingTheAllowed) {
    ColourField field = ColourField::all().front();
    for (std::size_t i = 0; i < ColourField::all().size(); ++i) {
        EXPECT_EQ(field, ColourField::all()[i]);
        field = nextColourField(field);
    }
    EXPECT_EQ(field, ColourField::all().front());
    try {
        parseColourField("vorticity");
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("'vorticity'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("speed, density, pressure"), std::string::npos);
    }
}

TEST(ColourFields, ValuesAreScalarsOrVectorMagnitudes) {
    HostParticles p;
    p.resize(2);
    p.vx = {3, 0};
    p.vy = {4, 0};
    p.vz = {0, -2};
    p.rho = {1000, 990};
    p.p = {5, 0};
    EXPECT_EQ(fieldValues(p, ColourField::Speed), (std::vector<float>{5, 2}));
    EXPECT_EQ(fieldValues(p, ColourField::Density), (std::vector<float>{1000, 990}));
    EXPECT_EQ(fieldValues(p, ColourField::Pressure), (std::vector<float>{5, 0}));
    // A magnitude's range starts at 0; a scalar's at its low percentile.
    EXPECT_EQ(robustRange(fieldValues(p, ColourField::Speed), ColourField::Speed).lo, 0.0);
    EXPECT_EQ(robustRange(fieldValues(p, ColourField::Density), ColourField::Density).lo, 990.0);
    const ValueRange speed = physicalRange(ColourField::Speed, 1000, 2.5, 5000);
    EXPECT_EQ(speed.hi, 2.5);
    EXPECT_EQ(physicalRange(ColourField::Pressure, 1000, 2.5, 5000).hi, 5000);
    EXPECT_NEAR(physicalRange(ColourField::Density, 1000, 2.5, 5000).lo, 900, 1e-9);
}

}  // namespace
}  // namespace weir
