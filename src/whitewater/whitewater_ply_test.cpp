// whitewater_NNNNN.ply: what is written reads back bit for bit; a broken file is refused with
// its name and what is wrong.
#include "whitewater/whitewater_ply.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace weir {
namespace {

namespace fs = std::filesystem;

class WhitewaterPly : public ::testing::Test {
   protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("weir_whitewater_ply_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

TEST_F(WhitewaterPly, RoundTripsEveryColumn) {
    DiffuseParticles p;
    p.push(0.1f, 0.2f, 0.3f, -1.5f, 2.25f, 1e-7f, DiffuseKind::Spray, 0.75f);
    p.push(-3.0f, 1e6f, 0.0f, 0.0f, -0.0f, 7.0f, DiffuseKind::Foam, -0.01f);
    p.push(1.0f / 3.0f, 2.0f / 3.0f, 5.0f, 9.0f, 8.0f, 7.0f, DiffuseKind::Bubble, 3.5f);
    const std::string path = (dir_ / "whitewater_00003.ply").string();
    writeWhitewaterPly(path, p);
    const DiffuseParticles q = readWhitewaterPly(path);
    ASSERT_EQ(q.size(), p.size());
    EXPECT_EQ(q.x, p.x);
    EXPECT_EQ(q.y, p.y);
    EXPECT_EQ(q.z, p.z);
    EXPECT_EQ(q.vx, p.vx);
    EXPECT_EQ(q.vy, p.vy);
    EXPECT_EQ(q.vz, p.vz);
    EXPECT_EQ(q.kind, p.kind);
    EXPECT_EQ(q.lifetime, p.lifetime);
    // Exactly the file: no temporary left beside it.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(WhitewaterPly, EmptyFrameRoundTrips) {
    const std::string path = (dir_ / "empty.ply").string();
    writeWhitewaterPly(path, DiffuseParticles{});
    EXPECT_EQ(readWhitewaterPly(path).size(), 0u);
}

TEST_F(WhitewaterPly, TruncatedOrForeignFilesAreRefusedByName) {
    DiffuseParticles p;
    p.push(1, 2, 3, 4, 5, 6, DiffuseKind::Foam, 1);
    p.push(1, 2, 3, 4, 5, 6, DiffuseKind::Foam, 1);
    const std::string path = (dir_ / "cut.ply").string();
    writeWhitewaterPly(path, p);
    fs::resize_file(path, fs::file_size(path) - 5);
    try {
        readWhitewaterPly(path);
        FAIL() << "a truncated file was read";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("cut.ply"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
    }
    const std::string other = (dir_ / "other.ply").string();
    std::ofstream(other) << "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n";
    EXPECT_THROW(readWhitewaterPly(other), IoError);
    EXPECT_THROW(readWhitewaterPly((dir_ / "missing.ply").string()), IoError);
}

}  // namespace
}  // namespace weir
