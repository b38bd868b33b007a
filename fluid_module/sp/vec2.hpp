// A pair of doubles, (x, y) of one vector, in one SSE2 register (GCC/Clang vector extension; on
// other targets the compiler splits it), for the hot passes over the pairs (the operators of
// sp/operators.hpp, sp/step_operator.cpp). Lane k of every vector operation is the scalar operation of component
// k, in the same order, so the results keep the bits of the scalar formulas
// (tests/fluid/operator_bits_test.cpp); SSE2 has no fused multiply-add that could change them.
#pragma once

#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace rockcut::fluid::sp {

typedef double Vec2 __attribute__((vector_size(16)));

inline Vec2 load2(const double* p) {
  Vec2 v;
  std::memcpy(&v, p, sizeof v);  // an unaligned load (movupd)
  return v;
}

/// Two floats widened to doubles (movq + cvtps2pd; exact). The step's per-pair coefficients are
/// stored as floats (sp/step_operator.hpp).
inline Vec2 load2f(const float* p) {
#if defined(__SSE2__)
  return (Vec2)_mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))));
#else
  typedef float Vec2f __attribute__((vector_size(8)));
  Vec2f v;
  std::memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, Vec2);
#endif
}

/// x rounded to float, in a form the optimiser cannot widen back. GCC 12's vectorizer folds
/// (double)(float)x to x (measured at -O2 and -O3: a sum of the rounded values came out as the
/// sum of the unrounded ones); the empty asm hides the float's origin and costs nothing.
inline float opaque_float(double x) {
  float f = static_cast<float>(x);
#if defined(__SSE2__)
  asm("" : "+x"(f));
#else
  asm("" : "+m"(f));
#endif
  return f;
}

}  // namespace rockcut::fluid::sp
