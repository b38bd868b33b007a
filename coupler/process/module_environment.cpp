#include "process/module_environment.hpp"

#include <cstdlib>

namespace rockcut::coupler {

void prepare_module_environment(bool coupled) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (coupled) setenv("OMP_WAIT_POLICY", "PASSIVE", /*overwrite=*/0);
}

}  // namespace rockcut::coupler
