// Numbers in messages: 4 significant digits.
#pragma once

#include <cstdio>
#include <string>

namespace rockcut::fluid::sp {

inline std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace rockcut::fluid::sp
