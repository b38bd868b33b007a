# Google Benchmark (Debian: libbenchmark-dev) for the bench/ programs.
find_package(benchmark QUIET CONFIG)
if(NOT benchmark_FOUND)
  message(FATAL_ERROR "Google Benchmark not found. Install: apt-get install libbenchmark-dev (or run scripts/setup), "
                      "or configure with -DROCKCUT_BUILD_BENCH=OFF.")
endif()
