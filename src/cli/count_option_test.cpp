// Counts on the command line: suffixes and exponents, whole numbers only, and range errors that
// name the option, the value and the limit.
#include "cli/count_option.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace weir {
namespace {

std::string errorOf(const std::string& text, std::int64_t min = 1,
                    std::int64_t max = kMaxParticles) {
    try {
        parseCount(text, "--particles", min, max, kParticleLimitText);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

TEST(CountOption, TakesSuffixesAndExponents) {
    const auto count = [](const std::string& text) {
        return parseCount(text, "--particles", 1, kMaxParticles);
    };
    EXPECT_EQ(count("20000"), 20000);
    EXPECT_EQ(count("20k"), 20000);
    EXPECT_EQ(count("20K"), 20000);
    EXPECT_EQ(count("5M"), 5000000);
    EXPECT_EQ(count("1e9"), 1000000000);
    EXPECT_EQ(count("1B"), 1000000000);
    EXPECT_EQ(count("1G"), 1000000000);
    EXPECT_EQ(count("1.5k"), 1500);
    EXPECT_EQ(count("2.5e3"), 2500);
    EXPECT_EQ(count(std::to_string(kMaxParticles)), kMaxParticles);
    EXPECT_EQ(parseCount("0", "--frames", 0, 10), 0);
}

TEST(CountOption, RefusesWhatIsNotACountNamingTheOptionAndTheLimit) {
    const std::string tooMany = errorOf("5e9");
    EXPECT_NE(tooMany.find("--particles"), std::string::npos) << tooMany;
    EXPECT_NE(tooMany.find("5e9"), std::string::npos) << tooMany;
    EXPECT_NE(tooMany.find("2147483647"), std::string::npos) << tooMany;
    EXPECT_NE(tooMany.find("32-bit"), std::string::npos) << tooMany;
    EXPECT_NE(errorOf("0").find("less than 1"), std::string::npos) << errorOf("0");
    EXPECT_NE(errorOf("-5").find("not a count"), std::string::npos) << errorOf("-5");
    EXPECT_NE(errorOf("20x").find("e.g. 20000, 20k, 5M or 1e9"), std::string::npos);
    EXPECT_NE(errorOf("1.2345k").find("not a whole number"), std::string::npos);
    EXPECT_NE(errorOf("").find("not a count"), std::string::npos);
}

TEST(CountOption, RewritesTheTextForCli11) {
    CLI::Validator validator = countOption(1, 1000);
    std::string text = "1k";
    EXPECT_EQ(validator(text), "");
    EXPECT_EQ(text, "1000");
    std::string over = "2k";
    EXPECT_NE(validator(over), "");
}

}  // namespace
}  // namespace weir
