# CLI11 command-line parser, header only (Debian: libcli11-dev).
find_package(CLI11 2.1 QUIET CONFIG)
if(NOT CLI11_FOUND)
  message(FATAL_ERROR "CLI11 not found. Install: apt-get install libcli11-dev (or run scripts/run).")
endif()
