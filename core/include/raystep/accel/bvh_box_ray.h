// The ray as the BVH's box tests read it: the slab test of geometry/bounds.h (intersect_slabs) prepared once
// per ray for the many boxes of one walk, for one box (hit) or for an inner node's two children at once
// (hit_children: 4-wide SIMD over the pair's rows, bvh_pair.h). Both make the same float operations in the
// same order as intersect_slabs, so the same answers: conservative (never a miss where the exact segment
// meets the box), +0 and -0 alike, NaN rays miss, a parallel ray outside a slab misses.
#pragma once

#include <cmath>

#include "raystep/accel/bvh_pair.h"
#include "raystep/geometry/bounds.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace raystep {

struct BvhBoxRay {
  // Ize's widening (bounds.h): a positive distance is scaled by kDown on the near side, kUp on the far side,
  // and the other way round for a negative one.
  static constexpr float kDown = 1.f - 2.f * gamma(3);
  static constexpr float kUp = 1.f + 2.f * gamma(3);

  glm::vec3 origin, inv_dir;
  int near_hi[3];  // 1: the near plane is the box's upper one (negative direction, or -0)
  float tmin, tmax;
  bool valid;

  explicit BvhBoxRay(const SlabRay& r)
      : origin(r.origin), inv_dir(r.inv_dir), tmin(r.tmin), tmax(r.tmax), valid(r.valid) {
    for (int a = 0; a < 3; ++a) near_hi[a] = std::signbit(r.inv_dir[a]) ? 1 : 0;
#if defined(__SSE2__)
    for (int a = 0; a < 3; ++a) {
      o_[a] = _mm_set1_ps(origin[a]);
      inv_[a] = _mm_set1_ps(inv_dir[a]);
      near_offset_[a] = near_hi[a] ? 8 : 0;
    }
    set_tmax(tmax);
#endif
  }

  // The walk's tmax shrinks to just beyond the nearest hit.
  void set_tmax(float t) {
    tmax = t;
#if defined(__SSE2__)
    start_ = _mm_setr_ps(tmin, tmin, -tmax, -tmax);
#endif
  }

  bool hit(const Bounds3& b, float* t_enter, float* t_exit) const {
    const glm::vec3* planes = &b.lo;  // planes[0] = lo, planes[1] = hi
    float t0 = tmin, t1 = tmax;
    for (int a = 0; a < 3; ++a) {
      float t_near = (planes[near_hi[a]][a] - origin[a]) * inv_dir[a];
      float t_far = (planes[1 - near_hi[a]][a] - origin[a]) * inv_dir[a];
      t_near *= t_near > 0.f ? kDown : kUp;
      t_far *= t_far > 0.f ? kUp : kDown;
      t0 = t_near > t0 ? t_near : t0;
      t1 = t_far < t1 ? t_far : t1;
    }
    *t_enter = t0;
    *t_exit = t1;
    return t0 <= t1 && t0 != kInfinity;
  }

  // Both children of an inner node: bit k of the result is set when child k's box is hit, and
  // [t_enter[k], t_exit[k]] is then what hit() gives for that box (and on a miss too).
  int hit_children(const BvhPair& p, float t_enter[2], float t_exit[2]) const {
#if defined(__SSE2__)
    // Lanes: left near, right near, left far, right far. A far distance is carried negated, so that one
    // maximum narrows both ends: -t1 = max(-t_far, -t1) is t1 = min(t_far, t1), NaN leaving it unchanged
    // alike (maxps keeps its second operand when either is NaN), and negation is exact. Ize's widening
    // without asking the sign: of t * kDown and t * kUp the smaller is the one towards -inf, which is the
    // product hit() picks by the sign (so the same bits), and one dependent step shorter.
    const __m128 down_up = _mm_setr_ps(kDown, kDown, -kUp, -kUp);
    const __m128 up_down = _mm_setr_ps(kUp, kUp, -kDown, -kDown);
    __m128 acc = start_;
    for (int a = 0; a < 3; ++a) {
      // The near planes (the lower ones, or the upper ones for a negative direction) into the low half, the
      // far ones into the high half: two 8-byte loads at offsets chosen once per ray.
      const char* row = reinterpret_cast<const char*>(p.rows[a]);
      __m128 planes = _mm_loadl_pi(_mm_setzero_ps(), reinterpret_cast<const __m64*>(row + near_offset_[a]));
      planes = _mm_loadh_pi(planes, reinterpret_cast<const __m64*>(row + 8 - near_offset_[a]));
      const __m128 t = _mm_mul_ps(_mm_sub_ps(planes, o_[a]), inv_[a]);
      acc = _mm_max_ps(_mm_min_ps(_mm_mul_ps(t, down_up), _mm_mul_ps(t, up_down)), acc);
    }
    // Hit: t_enter <= t_exit and t_enter != inf, lane by lane (NaN: a miss, as in hit()).
    const __m128 exits = _mm_xor_ps(_mm_shuffle_ps(acc, acc, _MM_SHUFFLE(3, 2, 3, 2)), _mm_set1_ps(-0.f));
    const __m128 hit = _mm_and_ps(_mm_cmple_ps(acc, exits), _mm_cmpneq_ps(acc, _mm_set1_ps(kInfinity)));
    alignas(16) float v[4];
    _mm_store_ps(v, acc);
    t_enter[0] = v[0];
    t_enter[1] = v[1];
    t_exit[0] = -v[2];
    t_exit[1] = -v[3];
    return _mm_movemask_ps(hit) & 3;
#else
    return hit_children_scalar(p, t_enter, t_exit);
#endif
  }

  // The same, one box after the other with hit(): the path of processors without SSE2, and the reference
  // that tests hold the SIMD path to.
  int hit_children_scalar(const BvhPair& p, float t_enter[2], float t_exit[2]) const {
    int hits = 0;
    for (int k = 0; k < 2; ++k) {
      Bounds3 b;
      for (int a = 0; a < 3; ++a) {
        b.lo[a] = p.rows[a][k];
        b.hi[a] = p.rows[a][k + 2];
      }
      hits |= int(hit(b, &t_enter[k], &t_exit[k])) << k;
    }
    return hits;
  }

 private:
#if defined(__SSE2__)
  __m128 o_[3], inv_[3], start_;
  int near_offset_[3];  // bytes into a pair's row where the near planes are
#endif
};

}  // namespace raystep
