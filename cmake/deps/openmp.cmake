# OpenMP for the particle and bond loops (part of GCC; libomp-dev for clang).
find_package(OpenMP QUIET COMPONENTS CXX)
if(NOT OpenMP_CXX_FOUND)
  message(WARNING "OpenMP not found: the DEM runs on one thread.")
endif()
