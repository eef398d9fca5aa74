#pragma once
// The shared test assets (../shared/assets: real heads, hair and glTF files made by other people),
// and what a test does when they are absent. On a developer's machine without the folder the test
// is skipped with a note; under CI (the environment variable CI=true, as CI services set it) the
// README's claims must be proven, so an absent asset FAILS the test instead of skipping it.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace wisp::test {

// $WISP_SHARED_ASSETS when set (tests/CMakeLists.txt proves the CI rule with it), else the folder
// beside the project that the build names.
inline std::filesystem::path sharedAssetsDir()
{
    if (const char* dir = std::getenv("WISP_SHARED_ASSETS"); dir != nullptr && *dir != '\0')
        return dir;
    return WISP_SHARED_ASSETS;
}

inline bool sharedAssetsRequired()
{
    const char* ci = std::getenv("CI");
    return ci != nullptr && (std::string_view(ci) == "true" || std::string_view(ci) == "1");
}

} // namespace wisp::test

// Use at the top of a test (or a fixture's SetUp) that needs `path` from the shared assets.
#define REQUIRE_SHARED_ASSET(path)                                                                                     \
    do {                                                                                                               \
        if (!std::filesystem::exists(path)) {                                                                          \
            if (::wisp::test::sharedAssetsRequired())                                                                  \
                FAIL() << "shared test asset " << (path) << " is absent, and CI=true requires every asset ("           \
                       << ::wisp::test::sharedAssetsDir() << ")";                                                      \
            else                                                                                                       \
                GTEST_SKIP() << "shared test asset " << (path) << " is absent (expected in "                           \
                             << ::wisp::test::sharedAssetsDir() << "); CI=true would fail here";                       \
        }                                                                                                              \
    } while (false)
