#include "process/module_environment.hpp"

#include <cstdlib>

namespace rockcut::coupler {

void prepare_module_environment(bool coupled, bool modules_take_turns) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (!coupled) return;
  if (modules_take_turns) {
    setenv("GOMP_SPINCOUNT", kTurnsSpinCount, /*overwrite=*/0);
  } else {
    setenv("OMP_WAIT_POLICY", "PASSIVE", /*overwrite=*/0);
  }
}

}  // namespace rockcut::coupler
