#include "core/thread_advice.hpp"

#include <algorithm>
#include <cstdio>

namespace rockcut::dem {

std::string thread_advice(std::size_t particles, int threads) {
  if (threads <= 1 || particles >= kMinParticlesPerThread * static_cast<std::size_t>(threads)) {
    return "";
  }
  // Most threads for which every thread still has kMinParticlesPerThread (at least 1).
  const std::size_t suggested = std::max<std::size_t>(1, particles / kMinParticlesPerThread);
  char line[320];
  std::snprintf(line, sizeof line,
                "dem.threads %d for %zu particles (%zu per thread): below about %zu per "
                "thread the threads' synchronisation at every step costs more than they save; "
                "dem.threads: %zu is likely faster",
                threads, particles, particles / static_cast<std::size_t>(threads),
                kMinParticlesPerThread, suggested);
  return line;
}

}  // namespace rockcut::dem
