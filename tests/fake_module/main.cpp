// fake_module: a DEM module from "another build" that speaks protocol version 999. The integration
// tests point a scene at it (dem.executable) to check that the handshake refuses it and names both
// sides.
#include "wire/module_main.hpp"
#include "wire/module_server.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

namespace {

class FakeDem final : public rockcut::wire::ModuleHandler {
 public:
  rockcut::wire::ModuleKind kind() const override { return rockcut::wire::MODULE_KIND_DEM; }
  std::string name() const override { return "fake_module"; }
  std::string version() const override { return "9.9.9"; }
  std::vector<std::string> models() const override { return {"dem"}; }
  void handle(const rockcut::wire::Message&, rockcut::wire::Message&) override {
    throw std::runtime_error("fake_module answers nothing but Hello");
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fake_module: speaks protocol 999 (for tests)"};
  std::string endpoint;
  app.add_option("--bind", endpoint)->required();
  CLI11_PARSE(app, argc, argv);
  FakeDem handler;
  zmq::context_t context(1);
  rockcut::wire::ServeOptions options;
  options.protocol_version = 999;
  return rockcut::wire::serve(context, endpoint, handler, options);
}
