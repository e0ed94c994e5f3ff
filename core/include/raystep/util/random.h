// raystep's random numbers: PCG32 (O'Neill, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
// Algorithms for Random Number Generation", 2014), a stream for each (seed, index), seeded through splitmix64
// (Steele et al. 2014). The sample patterns take one stream per pixel, so a pixel's samples depend on nothing
// else and an image is bit-identical whatever the thread count; the entry-probability measurements draw their
// random lines from one.
#pragma once

#include <cstdint>

namespace raystep {

// splitmix64's finaliser: a bijective mix of 64 bits.
inline uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

class Pcg32 {
 public:
  // Stream for (seed, index): the state from both, the increment (which selects the sequence) from the index.
  Pcg32(uint64_t seed, uint64_t index) {
    state_ = 0;
    inc_ = (mix64(index ^ 0x5851f42d4c957f2dull) << 1) | 1u;  // must be odd
    next_u32();
    state_ += mix64(seed ^ mix64(index));
    next_u32();
  }

  uint32_t next_u32() {
    // LCG step, then the output permutation XSH RR (xorshift high, random rotation) of the old state.
    uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    uint32_t xorshifted = uint32_t(((old >> 18) ^ old) >> 27);
    uint32_t rot = uint32_t(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
  }

  // Uniform in [0, 1): the top 24 bits, so every value is exact in float and below 1.
  float uniform() { return float(next_u32() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_, inc_;
};

}  // namespace raystep
