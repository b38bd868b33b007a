# GoogleTest (Debian: libgtest-dev, libgmock-dev).
find_package(GTest 1.10 QUIET CONFIG)
if(NOT GTest_FOUND)
  find_package(GTest QUIET)
endif()
if(NOT TARGET GTest::gtest_main)
  message(FATAL_ERROR "GoogleTest not found. Install: apt-get install libgtest-dev (or run scripts/test), "
                      "or configure with -DROCKCUT_BUILD_TESTS=OFF.")
endif()
include(GoogleTest)
