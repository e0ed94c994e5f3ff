// How much of a battery a core test runs. The Release pass runs every battery in full. The sanitizer passes
// (ASan + UBSan, TSan) run the same code several times slower, and look for memory errors, undefined
// behaviour and races, which show on every code path a battery reaches rather than on every ray: there the
// biggest batteries run a quarter of their rays or pixels (tests/CMakeLists.txt defines RAYSTEP_SANITIZED).
#pragma once

namespace raystep::test {

#ifdef RAYSTEP_SANITIZED
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

// n in the Release pass, a quarter of n (at least 1) in a sanitizer pass.
constexpr int budget(int n) {
  return kSanitized ? (n / 4 > 0 ? n / 4 : 1) : n;
}

}  // namespace raystep::test
