# GoogleTest (Debian: libgtest-dev, libgmock-dev).
find_package(GTest 1.10 QUIET CONFIG)
if(NOT TARGET GTest::gtest_main)
  message(FATAL_ERROR "GoogleTest not found. Install: apt-get install libgtest-dev libgmock-dev (or run scripts/test), "
                      "or configure with -DROCKCUT_BUILD_TESTS=OFF.")
endif()
include(GoogleTest)
