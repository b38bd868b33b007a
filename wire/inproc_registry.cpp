#include "wire/inproc_registry.hpp"

#include <map>

namespace rockcut::wire {

namespace {
std::map<ModuleKind, InprocServeFn>& registry() {
  static std::map<ModuleKind, InprocServeFn> modules;  // function-local: safe during static init
  return modules;
}
}  // namespace

bool register_inproc_module(ModuleKind kind, InprocServeFn fn) {
  registry()[kind] = fn;
  return true;
}

InprocServeFn find_inproc_module(ModuleKind kind) {
  auto it = registry().find(kind);
  return it == registry().end() ? nullptr : it->second;
}

}  // namespace rockcut::wire
