# ZeroMQ with the cppzmq header (Debian: libzmq3-dev, cppzmq-dev).
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(LIBZMQ QUIET IMPORTED_TARGET libzmq>=4.3)
endif()
find_path(CPPZMQ_INCLUDE_DIR zmq.hpp)
if(NOT LIBZMQ_FOUND OR NOT CPPZMQ_INCLUDE_DIR)
  message(FATAL_ERROR "ZeroMQ >= 4.3 with cppzmq not found. "
                      "Install: apt-get install libzmq3-dev cppzmq-dev pkg-config (or run scripts/run).")
endif()
add_library(rockcut_zmq INTERFACE)
target_include_directories(rockcut_zmq INTERFACE ${CPPZMQ_INCLUDE_DIR})
target_link_libraries(rockcut_zmq INTERFACE PkgConfig::LIBZMQ)
message(STATUS "libzmq ${LIBZMQ_VERSION}, cppzmq in ${CPPZMQ_INCLUDE_DIR}")
