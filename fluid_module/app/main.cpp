// fluid_module: the pore-pressure process. `fluid_module --bind ENDPOINT` serves one coupler session.
#include "service/fluid_service.hpp"
#include "wire/module_main.hpp"

int main(int argc, char** argv) {
  rockcut::fluid::FluidService service;
  return rockcut::wire::module_main(argc, argv, service);
}
