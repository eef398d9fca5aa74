#pragma once
// What the io tests share: the path of a file in ../shared/assets (real files made by other
// people; absent: a skip, or a failure under CI, see tests/SharedAssets.h), reading a whole file and
// a mesh's signed volume.

#include "../SharedAssets.h"
#include "sim/geometry/TriangleMesh.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <unistd.h>
#include <vector>

namespace wisp::test {

inline std::filesystem::path assetPath(const std::string& relative)
{
    return sharedAssetsDir() / relative;
}

inline std::string slurp(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

// The folders freshTestFolder made, removed when the test program ends (a test that wrote its
// files there and ended without a TearDown of its own left them in the temporary folder, a few
// every run).
struct TestFolders {
    std::vector<std::filesystem::path> made;
    ~TestFolders()
    {
        for (const std::filesystem::path& dir : made) {
            std::error_code ignored;
            std::filesystem::remove_all(dir, ignored);
        }
    }
};
inline TestFolders& testFolders()
{
    static TestFolders folders;
    return folders;
}

// An empty folder of its own for the running test (named after it and this process), made anew,
// and removed with what is in it when the test program ends.
inline std::filesystem::path freshTestFolder(const std::string& prefix)
{
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir = std::filesystem::temp_directory_path()
        / (prefix + "-" + std::to_string(::getpid()) + "-" + std::string(test->name()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    testFolders().made.push_back(dir);
    return dir;
}

// The enclosed volume, positive when triangles wind counter-clockwise seen from outside.
inline double signedVolume(const TriangleMesh& mesh)
{
    double v = 0.0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

} // namespace wisp::test

#define REQUIRE_ASSET(path) REQUIRE_SHARED_ASSET(path)
