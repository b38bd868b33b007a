// dem_module: the discrete-element process. `dem_module --bind ENDPOINT` serves one coupler session.
#include <cstdlib>

#include "service/dem_service.hpp"
#include "wire/module_main.hpp"

int main(int argc, char** argv) {
  // The OpenMP wait policy is not set here: libgomp reads OMP_WAIT_POLICY when it is loaded,
  // before main. The coupler puts OMP_WAIT_POLICY=PASSIVE in the environment of the module
  // processes it starts (coupler/cli/main.cpp); started by hand, set it yourself.
  rockcut::dem::DemService service;
  return rockcut::wire::module_main(argc, argv, service);
}
