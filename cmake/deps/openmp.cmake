# OpenMP for the particle, bond and SP loops (part of GCC; libomp-dev for clang).
find_package(OpenMP QUIET COMPONENTS CXX)
if(NOT OpenMP_CXX_FOUND)
  message(FATAL_ERROR "OpenMP not found. GCC has it; with clang install libomp-dev.")
endif()
