// A pair of doubles, (x, y) of one vector, in one SSE2 register (GCC/Clang vector extension; on
// other targets the compiler splits it), for the hot passes over the pairs (sp/operators.cpp,
// sp/step_operator.cpp). Lane k of every vector operation is the scalar operation of component
// k, in the same order, so the results keep the bits of the scalar formulas
// (tests/fluid/operator_bits_test.cpp); SSE2 has no fused multiply-add that could change them.
#pragma once

#include <cstring>

namespace rockcut::fluid::sp {

typedef double Vec2 __attribute__((vector_size(16)));

inline Vec2 load2(const double* p) {
  Vec2 v;
  std::memcpy(&v, p, sizeof v);  // an unaligned load (movupd)
  return v;
}

}  // namespace rockcut::fluid::sp
