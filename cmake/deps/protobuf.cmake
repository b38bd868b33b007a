# Protocol Buffers: libprotobuf and protoc (Debian: libprotobuf-dev, protobuf-compiler).
find_package(Protobuf 3.12 QUIET)
if(NOT Protobuf_FOUND OR NOT Protobuf_PROTOC_EXECUTABLE)
  message(FATAL_ERROR "Protocol Buffers (library and protoc) not found. "
                      "Install: apt-get install libprotobuf-dev protobuf-compiler (or run scripts/run).")
endif()
message(STATUS "protobuf ${Protobuf_VERSION}, protoc ${Protobuf_PROTOC_EXECUTABLE}")
