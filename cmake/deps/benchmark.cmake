# Google Benchmark (Debian: libbenchmark-dev); the bench/ programs are skipped without it.
find_package(benchmark QUIET CONFIG)
if(NOT benchmark_FOUND)
  message(STATUS "Google Benchmark not found: bench/ is not built (apt-get install libbenchmark-dev).")
endif()
