// Obstacle mesh files: numbers, indices and counts are range checked, and every refusal names the
// file, the line (or binary STL triangle), the value and what is allowed.
#include "scene/mesh_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace weir {
namespace {

namespace fs = std::filesystem;

class MeshFileTest : public ::testing::Test {
   protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("weir_mesh_file_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string write(const std::string& name, const std::string& bytes) const {
        std::ofstream(dir_ / name, std::ios::binary) << bytes;
        return (dir_ / name).string();
    }
    // The message of the error readMeshFile throws for `bytes` written as `name`.
    std::string error(const std::string& name, const std::string& bytes) const {
        const std::string path = write(name, bytes);
        try {
            readMeshFile(path);
        } catch (const std::runtime_error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(path), std::string::npos) << message;
            return message;
        }
        ADD_FAILURE() << name << " was accepted";
        return "";
    }
    fs::path dir_;
};

// A binary STL of one triangle whose first vertex's x is `x`.
std::string binaryStl(float x) {
    std::string bytes(84 + 50, '\0');
    const std::uint32_t count = 1;
    std::memcpy(&bytes[80], &count, 4);
    const float corners[9] = {x, 0, 0, 1, 0, 0, 0, 1, 0};
    std::memcpy(&bytes[84 + 12], corners, sizeof corners);
    return bytes;
}

TEST_F(MeshFileTest, BinaryStlRefusesNonFiniteAndHugeCoordinates) {
    EXPECT_EQ(readMeshFile(write("ok.stl", binaryStl(0.5f))).triangles.size(), 1u);
    for (float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 3e38f}) {
        const std::string message = error("bad.stl", binaryStl(bad));
        EXPECT_NE(message.find("triangle 1 of 1"), std::string::npos) << message;
        EXPECT_NE(message.find("vertex 1 x"), std::string::npos) << message;
        EXPECT_NE(message.find("finite"), std::string::npos) << message;
    }
    EXPECT_NE(error("nan.stl", binaryStl(NAN)).find("is nan"), std::string::npos);
}

TEST_F(MeshFileTest, BinaryStlCountBeyondTheFileIsRefusedBeforeAllocating) {
    std::string bytes(100, '\0');
    const std::uint32_t count = 4000000000u;
    std::memcpy(&bytes[80], &count, 4);
    const std::string message = error("huge.stl", bytes);
    EXPECT_NE(message.find("4000000000 triangles"), std::string::npos) << message;
    EXPECT_NE(message.find("the file has 100"), std::string::npos) << message;
}

TEST_F(MeshFileTest, ObjFaceIndicesAreRangeChecked) {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    std::string message = error("big.obj", vertices + "f 1 2 99999999999999999999\n");
    EXPECT_NE(message.find("line 4"), std::string::npos) << message;
    EXPECT_NE(message.find("'99999999999999999999'"), std::string::npos) << message;
    EXPECT_NE(message.find("1..3"), std::string::npos) << message;
    message = error("wrap.obj", vertices + "f 1 2 4294967299\n");  // 2^32 + 3 would wrap to 3
    EXPECT_NE(message.find("'4294967299'"), std::string::npos) << message;
    message = error("text.obj", vertices + "f 1 2 3x\n");
    EXPECT_NE(message.find("'3x' is not an integer"), std::string::npos) << message;
    message = error("zero.obj", vertices + "f 0 1 2\n");
    EXPECT_NE(message.find("names no vertex"), std::string::npos) << message;
    message = error("normal.obj", vertices + "f 1//a 2 3\n");
    EXPECT_NE(message.find("'a'"), std::string::npos) << message;
    // Negative indices count back from the last vertex; texture and normal parts are allowed.
    const MeshData mesh =
        readMeshFile(write("ok.obj", vertices + "f -3 -2 -1\nf 1/1 2//2 3/3/3\n"));
    EXPECT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.triangles[0], (std::array<int, 3>{0, 1, 2}));
}

TEST_F(MeshFileTest, ObjAndAsciiStlRefuseBadNumbers) {
    for (const char* bad : {"nan", "inf", "1e400", "1e10", "0x1p3", "1,5"}) {
        std::string message = error("bad.obj", std::string("v 0 0 0\nv 1 0 ") + bad + "\n");
        EXPECT_NE(message.find("line 2"), std::string::npos) << message;
        EXPECT_NE(message.find(std::string("'") + bad + "'"), std::string::npos) << message;
        message = error("bad.stl", std::string("solid s\nfacet normal 0 0 1\nouter loop\n") +
                                       "vertex 0 0 0\nvertex 1 0 " + bad +
                                       "\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n");
        EXPECT_NE(message.find("line 5"), std::string::npos) << message;
        EXPECT_NE(message.find("vertex z"), std::string::npos) << message;
    }
    EXPECT_NE(error("short.obj", "v 1 2\n").find("three numbers"), std::string::npos);
    EXPECT_NE(error("tiny.stl", "abc").find("neither ASCII STL"), std::string::npos);
    EXPECT_NE(error("empty.obj", "# nothing\n").find("no triangles"), std::string::npos);
}

}  // namespace
}  // namespace weir
