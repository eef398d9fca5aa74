// The GUI tests' entry point: GoogleTest inside a QApplication, because widgets need one.
//
// CMake's gtest_discover_tests runs this binary with --gtest_list_tests at build time, where there
// may be no display: listing tests needs no QApplication, so none is made for it.

#include <QApplication>

#include <gtest/gtest.h>

#include <cstring>

int main(int argc, char** argv)
{
    bool listing = false;
    for (int i = 1; i < argc; ++i)
        listing = listing || std::strcmp(argv[i], "--gtest_list_tests") == 0;
    if (listing) {
        testing::InitGoogleTest(&argc, argv);
        return RUN_ALL_TESTS();
    }
    QApplication app(argc, argv);
    testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
