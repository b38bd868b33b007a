#include "wire/module_main.hpp"

#include <malloc.h>

#include <csignal>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "wire/curve_keys.hpp"

namespace rockcut::wire {

void tune_allocator_for_bulk_frames() {
  mallopt(M_MMAP_THRESHOLD, 256 << 20);  // blocks below 256 MiB come from the heap
  mallopt(M_TRIM_THRESHOLD, 1 << 30);    // and the heap is not trimmed below 1 GiB of free space
}

int module_main(int argc, char** argv, ModuleHandler& handler) {
  tune_allocator_for_bulk_frames();
  // Its stdout and stderr are the coupler's, or a terminal's when started by hand: if their reader
  // has gone, a write fails instead of killing the module (as in the coupler, run/signals.hpp).
  signal(SIGPIPE, SIG_IGN);
  CLI::App app{handler.name() + " " + handler.version() +
               ": a rockcut module. Normally started by `coupler run`; start it by hand to attach "
               "a coupler over tcp (`coupler run CASE --transport tcp ...`)."};
  std::string endpoint = "tcp://127.0.0.1:5555";
  app.add_option("--bind", endpoint,
                 "ZeroMQ endpoint to serve on, e.g. tcp://127.0.0.1:5555 or ipc:///tmp/x.sock")
      ->capture_default_str();
  std::string keys_dir;
  app.add_option("--curve-keys", keys_dir,
                 "Key directory (made by `coupler keygen DIR`): serve with CURVE security, with "
                 "this module's key pair from it, accepting only the coupler's public key "
                 "(coupler.public). Without it the module serves without authentication: keep it "
                 "on loopback");
  std::string read_under;
  app.add_option("--read-under", read_under,
                 "Over tcp: the directory under which this module reads the files a coupler's "
                 "scene names (the DEM's packing file); default: the working directory. A peer "
                 "cannot make the module read anything outside it");
  ServeOptions options;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (!keys_dir.empty()) {
    try {
      options.curve_secret_key = read_key_pair(keys_dir, handler.name()).secret_key;
      options.curve_client_key = read_public_key(keys_dir, "coupler");
    } catch (const std::exception& e) {
      std::cerr << handler.name() << ": " << e.what() << "\n";
      return 2;
    }
  }
  if (endpoint.rfind("ipc://", 0) != 0) {
    std::error_code ec;
    const std::filesystem::path root =
        std::filesystem::canonical(read_under.empty() ? std::filesystem::current_path(ec)
                                                      : std::filesystem::path(read_under),
                                   ec);
    if (ec || !std::filesystem::is_directory(root, ec)) {
      std::cerr << handler.name() << ": --read-under " << read_under
                << ": not a directory this module can open\n";
      return 2;
    }
    handler.set_read_root(root);
  }
  try {
    zmq::context_t context(1);
    return serve(context, endpoint, handler, options);
  } catch (const zmq::error_t& e) {
    std::cerr << handler.name() << ": cannot serve on " << endpoint << ": " << e.what() << "\n";
    return 2;
  }
}

}  // namespace rockcut::wire
