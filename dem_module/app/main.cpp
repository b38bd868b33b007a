// dem_module: the discrete-element process. `dem_module --bind ENDPOINT` serves one coupler session.
#include <cstdlib>

#include "service/dem_service.hpp"
#include "wire/module_main.hpp"

int main(int argc, char** argv) {
  // OpenMP threads that sleep at barriers instead of spinning: the DEM shares the cores with the
  // fluid process and the coupler, and spinning threads of an oversubscribed team stall each
  // other by orders of magnitude (measured: 2 threads 20x slower than 1 under load). An explicit
  // OMP_WAIT_POLICY in the environment still wins.
  setenv("OMP_WAIT_POLICY", "PASSIVE", /*overwrite=*/0);
  rockcut::dem::DemService service;
  return rockcut::wire::module_main(argc, argv, service);
}
