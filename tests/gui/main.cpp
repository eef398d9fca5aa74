// The GUI tests' entry point: GoogleTest inside a QApplication, because widgets need one.
//
// CMake's gtest_discover_tests runs this binary with --gtest_list_tests at build time, where there
// may be no display: listing tests needs no QApplication, so none is made for it.

#include "widgets/HeapPolicy.h"

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
    wisp::keepFreedHeapForReuse(); // as the editor does (widgets/HeapPolicy.h)
    QApplication app(argc, argv);
    testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}

#if defined(__SANITIZE_ADDRESS__)
// Qt's D-Bus link and Mesa's driver (unloaded at exit, so its frames have no symbols) leave a few
// allocations LeakSanitizer cannot attribute or suppress by name; GUI test processes run without
// leak detection. The sim, io and CLI tests keep it. ASAN_OPTIONS in the environment still wins.
extern "C" const char* __asan_default_options()
{
    return "detect_leaks=0";
}
#endif
