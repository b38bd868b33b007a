// fluid_module: the pore-pressure process. `fluid_module --bind ENDPOINT` serves one coupler session.
#include <cstdlib>

#include "service/fluid_service.hpp"
#include "wire/module_main.hpp"

int main(int argc, char** argv) {
  // Idle OpenMP threads sleep instead of spinning: the DEM process shares the cores and works
  // while this one waits. OMP_WAIT_POLICY in the environment still wins.
  setenv("OMP_WAIT_POLICY", "PASSIVE", /*overwrite=*/0);
  rockcut::fluid::FluidService service;
  return rockcut::wire::module_main(argc, argv, service);
}
