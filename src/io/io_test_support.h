// Test helpers for the io tests: a per-test temporary directory and random particle frames.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/io_error.h"
#include "solver/particles.h"

namespace weir::test {

// A fresh directory under the system temp dir, named after the running test, removed at the end.
class TempDir {
   public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = std::filesystem::temp_directory_path() /
                ("weir_io_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                 std::to_string(::getpid()));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    // A path inside the directory.
    std::string operator/(const std::string& name) const { return (path_ / name).string(); }
    const std::filesystem::path& path() const { return path_; }

    // The names of the directory's entries, sorted.
    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& entry : std::filesystem::directory_iterator(path_)) {
            names.push_back(entry.path().filename().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

   private:
    std::filesystem::path path_;
};

inline HostParticles randomParticles(std::size_t n, unsigned seed = 1) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    HostParticles particles;
    particles.resize(n);
    for (auto* array : {&particles.x, &particles.y, &particles.z, &particles.vx, &particles.vy,
                        &particles.vz, &particles.rho, &particles.p}) {
        for (Real& value : *array) {
            value = Real(unit(rng) * 1e3);
        }
    }
    return particles;
}

// Puts values that text or conversion bugs mangle into the first particles: -0, infinities,
// NaN, the smallest denormal, the extremes.
inline void addSpecialValues(HostParticles& particles) {
    using Limits = std::numeric_limits<Real>;
    const Real specials[] = {Real(-0.0),          Limits::infinity(),   -Limits::infinity(),
                             Limits::quiet_NaN(), Limits::denorm_min(), Limits::max(),
                             Limits::lowest(),    Limits::epsilon()};
    std::size_t k = 0;
    for (auto* array : {&particles.x, &particles.y, &particles.z, &particles.vx, &particles.vy,
                        &particles.vz, &particles.rho, &particles.p}) {
        for (std::size_t i = 0; i < std::size(specials) && i < array->size(); ++i) {
            (*array)[i] = specials[(i + k) % std::size(specials)];
        }
        ++k;
    }
}

inline bool sameBits(const std::vector<Real>& a, const std::vector<Real>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)) == 0;
}

inline void expectSameBits(const HostParticles& expected, const HostParticles& actual) {
    EXPECT_TRUE(sameBits(expected.x, actual.x));
    EXPECT_TRUE(sameBits(expected.y, actual.y));
    EXPECT_TRUE(sameBits(expected.z, actual.z));
    EXPECT_TRUE(sameBits(expected.vx, actual.vx));
    EXPECT_TRUE(sameBits(expected.vy, actual.vy));
    EXPECT_TRUE(sameBits(expected.vz, actual.vz));
    EXPECT_TRUE(sameBits(expected.rho, actual.rho));
    EXPECT_TRUE(sameBits(expected.p, actual.p));
}

// Expects read(path) to throw an IoError whose message names path and contains `detail`.
template <class Read>
void expectIoError(Read read, const std::string& path, const std::string& detail) {
    try {
        read(path);
        ADD_FAILURE() << "no IoError for " << path;
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_NE(message.find(detail), std::string::npos) << message;
    }
}

inline std::string fileText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void writeText(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

}  // namespace weir::test
