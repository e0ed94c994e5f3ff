// Floating-point error bounds for robust ray tracing.
// gamma(n) bounds the relative error of n floating-point operations (Higham; pbrt-v4, section 6.8);
// next_float_up/down move to the neighbouring representable float. These replace fixed epsilons.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace raystep {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr float kMachineEpsilon = std::numeric_limits<float>::epsilon() * 0.5f;

// Relative error bound of n chained float operations: n*eps / (1 - n*eps).
constexpr float gamma(int n) { return (n * kMachineEpsilon) / (1 - n * kMachineEpsilon); }

// The same bound for n double operations: for the kernels that work in double on float inputs.
constexpr double kDoubleMachineEpsilon = std::numeric_limits<double>::epsilon() * 0.5;
constexpr double gamma_double(int n) { return (n * kDoubleMachineEpsilon) / (1 - n * kDoubleMachineEpsilon); }

inline uint32_t float_to_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}
inline float bits_to_float(uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

// The smallest float greater than v (+inf stays +inf; -0 becomes the smallest positive float).
inline float next_float_up(float v) {
  if (std::isinf(v) && v > 0.f) return v;
  if (v == -0.f) v = 0.f;
  uint32_t ui = float_to_bits(v);
  if (v >= 0) ++ui; else --ui;
  return bits_to_float(ui);
}

// The largest float smaller than v.
inline float next_float_down(float v) {
  if (std::isinf(v) && v < 0.f) return v;
  if (v == 0.f) v = -0.f;
  uint32_t ui = float_to_bits(v);
  if (v > 0) --ui; else ++ui;
  return bits_to_float(ui);
}

// a - b and a + b rounded towards -inf and +inf: the float nearest the exact result, stepped one ulp outwards
// only when rounding to nearest moved it inwards. The exact rounding error comes from Knuth's TwoSum (plain
// additions, so no FMA contraction can touch it). A box built this way keeps an exact face where one exists:
// a sphere resting on the plane y = 0 has its box start at 0, not at -1.4e-45.
inline float sub_round_down(float a, float b) {
  float s = a - b;
  float bv = s - a, av = s - bv;     // TwoSum(a, -b)
  float err = (a - av) + (-b - bv);  // s + err == a - b exactly
  return err < 0.f ? next_float_down(s) : s;
}
inline float add_round_up(float a, float b) {
  float s = a + b;
  float bv = s - a, av = s - bv;
  float err = (a - av) + (b - bv);  // s + err == a + b exactly
  return err > 0.f ? next_float_up(s) : s;
}

}  // namespace raystep
