#pragma once
// What the io tests share: the path of a file in ../shared/assets (real files made by other
// people), a skip with a clear message when that folder is absent, and reading a whole file.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace wisp::test {

inline std::filesystem::path assetPath(const std::string& relative)
{
    return std::filesystem::path(WISP_SHARED_ASSETS) / relative;
}

inline std::string slurp(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace wisp::test

// Skips the test, saying where the asset was expected, when it is not there.
#define REQUIRE_ASSET(path)                                                                                  \
    do {                                                                                                     \
        if (!std::filesystem::exists(path))                                                                  \
            GTEST_SKIP() << "shared test asset " << (path) << " is absent (expected beside the project in " \
                         << WISP_SHARED_ASSETS << ")";                                                       \
    } while (false)
