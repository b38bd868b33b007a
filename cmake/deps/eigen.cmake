# Eigen 3 (Debian: libeigen3-dev).
find_package(Eigen3 3.3 QUIET NO_MODULE)
if(NOT Eigen3_FOUND)
  message(FATAL_ERROR "Eigen 3 not found. Install: apt-get install libeigen3-dev (or run scripts/run).")
endif()
message(STATUS "Eigen ${Eigen3_VERSION}")
