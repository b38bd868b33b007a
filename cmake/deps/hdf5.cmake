# HDF5 C library (Debian: libhdf5-dev); FindHDF5 defines the hdf5::hdf5 target.
find_package(HDF5 1.10 QUIET COMPONENTS C)
if(NOT HDF5_FOUND)
  message(FATAL_ERROR "HDF5 not found. Install: apt-get install libhdf5-dev (or run scripts/run).")
endif()
message(STATUS "HDF5 ${HDF5_VERSION}")
