// dem_module: the discrete-element process. `dem_module --bind ENDPOINT` serves one coupler session.
#include "service/dem_service.hpp"
#include "wire/module_main.hpp"

int main(int argc, char** argv) {
  rockcut::dem::DemService service;
  return rockcut::wire::module_main(argc, argv, service);
}
