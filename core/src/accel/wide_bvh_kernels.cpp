// The wide BVH's kernels: one walk (wide_bvh_kernel.inc) compiled three times, with scalar lanes, with SSE
// and with AVX2 (the last under `#pragma GCC target`, so that only these functions use AVX2 and the program
// runs on any x86-64; the choice is made at run time, wide_bvh.cpp). Every version computes the box test of
// intersect_slabs (geometry/bounds.h) lane by lane with the same roundings, and the triangle filter the
// watertight test's own first steps (geometry/triangle.h) with the same roundings, so that the answers do not
// depend on the instruction set. No FMA: a fused multiply-add rounds once where the scalar code rounds twice.
#include <cmath>
#include <cstddef>
#include <limits>
#include <new>
#include <type_traits>

#include "raystep/record/event_recorder.h"
#include "wide_bvh_impl.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace raystep {

namespace {
constexpr float kMaxFloat = std::numeric_limits<float>::max();
// Ize's widening of the slab distances (bounds.h): down by 2 gamma(3) on one side of 0, up on the other.
constexpr float kDown = 1.f - 2.f * gamma(3);
constexpr float kUp = 1.f + 2.f * gamma(3);

// SlabRay (bounds.h) computed here, so that it is inlined into every kernel (a function of the default
// target is not inlined into the AVX2 one unless it must be): the same reciprocal, the same validity.
struct RayPrep {
  float origin[3], inv_dir[3];
  float tmin, tmax;
  bool valid;
};
[[gnu::always_inline]] inline RayPrep prepare(const Ray& r) {
  RayPrep p;
  const glm::vec3& d = r.direction;
  for (int a = 0; a < 3; ++a) {
    p.origin[a] = r.origin[a];
    p.inv_dir[a] = 1.f / d[a];
  }
  p.tmin = r.tmin;
  p.tmax = r.tmax;
  bool finite_dir = std::isfinite(d.x) & std::isfinite(d.y) & std::isfinite(d.z);
  bool nonzero_dir = (d.x != 0.f) | (d.y != 0.f) | (d.z != 0.f);
  bool finite_origin = std::isfinite(r.origin.x) & std::isfinite(r.origin.y) & std::isfinite(r.origin.z);
  p.valid = finite_origin & finite_dir & nonzero_dir & !std::isnan(r.tmin) & !std::isnan(r.tmax) &
            (r.tmin < r.tmax);
  return p;
}

// What the SIMD part of the watertight test found for a packet: `candidates` are the lanes not rejected;
// among them, `decided` are hits it proved (beyond tmin, before the packet's tmax), with their det, scaled t,
// t and barycentrics, computed with the scalar test's operations; the others go to the scalar test.
struct PacketResult {
  uint32_t candidates, decided;
  alignas(16) float det[kWidePacket], t_scaled[kWidePacket], t[kWidePacket], b1[kWidePacket], b2[kWidePacket];
};

// The watertight test of one triangle of a packet (triangle.h's intersect_triangle, with the vertices from
// the packet: the same floats as the geometry's).
[[gnu::always_inline]] inline bool packet_triangle(const WatertightRay& w, const TriPacket& p, int lane,
                                                   float tmax, TriangleHit* th) {
  glm::vec3 v0(p.v[0][lane], p.v[1][lane], p.v[2][lane]);
  glm::vec3 v1(p.v[3][lane], p.v[4][lane], p.v[5][lane]);
  glm::vec3 v2(p.v[6][lane], p.v[7][lane], p.v[8][lane]);
  switch (w.kz) {
    case 0:
      return detail::intersect_triangle_permuted<1, 2, 0>(w, v0, v1, v2, tmax, th);
    case 1:
      return detail::intersect_triangle_permuted<2, 0, 1>(w, v0, v1, v2, tmax, th);
    default:
      return detail::intersect_triangle_permuted<0, 1, 2>(w, v0, v1, v2, tmax, th);
  }
}
}  // namespace

// ---- Scalar lanes: any architecture ----
namespace wide_scalar {
namespace {

struct BoxRay {
  float origin[3], inv_dir[3];
  int near_row[3], far_row[3];
  float tmin;
  // False for a ray that meets nothing (RayPrep::valid).
  [[gnu::always_inline]] bool prepare(const Ray& ray) {
    const RayPrep r = raystep::prepare(ray);
    for (int a = 0; a < 3; ++a) {
      origin[a] = r.origin[a];
      inv_dir[a] = r.inv_dir[a];
      bool negative = std::signbit(r.inv_dir[a]);
      near_row[a] = 2 * a + (negative ? 1 : 0);
      far_row[a] = 2 * a + (negative ? 0 : 1);
    }
    tmin = r.tmin;
    return r.valid;
  }
};

inline float max_nan_first(float a, float b) {
  return a > b ? a : b;
}  // as maxps: b when either is NaN
inline float min_nan_first(float a, float b) {
  return a < b ? a : b;
}

template <int W>
inline uint32_t box_test(const WideNode<W>& n, const BoxRay& r, float tmin, float tmax, float* t_near_out,
                         float* t_far_out) {
  uint32_t mask = 0;
  for (int i = 0; i < W; ++i) {
    float t_near = -kInfinity, t_far = kInfinity;
    for (int a = 0; a < 3; ++a) {
      t_near = max_nan_first((n.box[r.near_row[a]][i] - r.origin[a]) * r.inv_dir[a], t_near);
      t_far = min_nan_first((n.box[r.far_row[a]][i] - r.origin[a]) * r.inv_dir[a], t_far);
    }
    // Ize's factor, after the max: it is monotonic, so widening the largest is widening each.
    float t0 = max_nan_first(min_nan_first(t_near * kDown, t_near * kUp), tmin);
    float t1 = min_nan_first(max_nan_first(t_far * kUp, t_far * kDown), tmax);
    t_near_out[i] = t0;
    if (t_far_out) t_far_out[i] = t1;
    mask |= uint32_t(t0 <= t1) << i;
  }
  return mask;
}

struct TriRay {
  void init(const WatertightRay&) {}
};
// No filter: every triangle goes to the watertight test.
inline void tri_filter(const TriPacket&, const TriRay&, float, PacketResult* out) {
  out->candidates = (1u << kWidePacket) - 1;
  out->decided = 0;
}

#include "wide_bvh_kernel.inc"

}  // namespace
}  // namespace wide_scalar

#if defined(__x86_64__)

// ---- SSE: 4 lanes (8-wide nodes as two halves); also the triangle filter of the AVX2 kernel ----
namespace wide_sse {
namespace {

// prepare() of the SIMD kernels: the ray's origin and direction as two vectors, the validity of RayPrep and
// the reciprocal (divps rounds as divss) with a few vector compares, the near rows from the sign mask.
// Ray is 32 bytes: origin, direction, tmin, tmax; the loads read ox oy oz dx and dx dy dz tmin.
static_assert(sizeof(Ray) == 32 && offsetof(Ray, direction) == 12 && offsetof(Ray, tmin) == 24,
              "prepare() loads the ray as floats");
struct RayVectors {
  __m128 origin, inv_dir;  // lanes 0-2
  float tmin;
  int sign;    // bit a: the direction on axis a is negative (or -0)
  bool valid;  // RayPrep::valid
};
[[gnu::always_inline]] inline RayVectors prepare_vectors(const Ray& ray) {
  RayVectors v;
  const __m128 o = _mm_loadu_ps(&ray.origin.x), d = _mm_loadu_ps(&ray.direction.x);
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff)), inf = _mm_set1_ps(kInfinity);
  // Finite origin and direction (a NaN compares false), a direction that is not zero (a NaN one is invalid
  // already), tmin < tmax (false when either is NaN).
  const int finite = _mm_movemask_ps(
      _mm_and_ps(_mm_cmplt_ps(_mm_and_ps(o, abs_mask), inf), _mm_cmplt_ps(_mm_and_ps(d, abs_mask), inf)));
  const int nonzero = _mm_movemask_ps(_mm_cmpneq_ps(d, _mm_setzero_ps()));
  v.valid = ((finite & 7) == 7) & ((nonzero & 7) != 0) & (ray.tmin < ray.tmax);
  v.origin = o;
  v.inv_dir = _mm_div_ps(_mm_set1_ps(1.f), d);  // lane 3: 1 / tmin, unused
  v.sign = _mm_movemask_ps(v.inv_dir) & 7;
  v.tmin = ray.tmin;
  return v;
}

struct BoxRay {
  __m128 origin[3], inv_dir[3];
  int near_row[3], far_row[3];
  float tmin;
  [[gnu::always_inline]] void set(const RayVectors& v) {
    origin[0] = _mm_shuffle_ps(v.origin, v.origin, 0x00);
    origin[1] = _mm_shuffle_ps(v.origin, v.origin, 0x55);
    origin[2] = _mm_shuffle_ps(v.origin, v.origin, 0xaa);
    inv_dir[0] = _mm_shuffle_ps(v.inv_dir, v.inv_dir, 0x00);
    inv_dir[1] = _mm_shuffle_ps(v.inv_dir, v.inv_dir, 0x55);
    inv_dir[2] = _mm_shuffle_ps(v.inv_dir, v.inv_dir, 0xaa);
    for (int a = 0; a < 3; ++a) {
      near_row[a] = 2 * a + ((v.sign >> a) & 1);
      far_row[a] = near_row[a] ^ 1;
    }
    tmin = v.tmin;
  }
  // False for a ray that meets nothing (RayPrep::valid).
  [[gnu::always_inline]] bool prepare(const Ray& ray) {
    const RayVectors v = prepare_vectors(ray);
    set(v);
    return v.valid;
  }
};

// Four lanes of intersect_slabs. maxps/minps return their second operand when either is NaN, so a NaN
// distance (0 * inf: the ray in a slab's plane) leaves the accumulated one unchanged, as in bounds.h.
template <int W>
inline uint32_t box_test4(const WideNode<W>& n, int off, const BoxRay& r, __m128 tmin, __m128 tmax,
                          float* t_near_out, float* t_far_out) {
  __m128 t_near = _mm_set1_ps(-kInfinity), t_far = _mm_set1_ps(kInfinity);
  for (int a = 0; a < 3; ++a) {
    __m128 dn = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(&n.box[r.near_row[a]][off]), r.origin[a]), r.inv_dir[a]);
    __m128 df = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(&n.box[r.far_row[a]][off]), r.origin[a]), r.inv_dir[a]);
    t_near = _mm_max_ps(dn, t_near);
    t_far = _mm_min_ps(df, t_far);
  }
  __m128 t0 = _mm_max_ps(
      _mm_min_ps(_mm_mul_ps(t_near, _mm_set1_ps(kDown)), _mm_mul_ps(t_near, _mm_set1_ps(kUp))), tmin);
  __m128 t1 = _mm_min_ps(
      _mm_max_ps(_mm_mul_ps(t_far, _mm_set1_ps(kUp)), _mm_mul_ps(t_far, _mm_set1_ps(kDown))), tmax);
  _mm_store_ps(t_near_out + off, t0);
  if (t_far_out) _mm_store_ps(t_far_out + off, t1);
  return uint32_t(_mm_movemask_ps(_mm_cmple_ps(t0, t1)));
}

template <int W>
inline uint32_t box_test(const WideNode<W>& n, const BoxRay& r, float tmin, float tmax, float* t_near_out,
                         float* t_far_out) {
  __m128 lo = _mm_set1_ps(tmin), hi = _mm_set1_ps(tmax);
  uint32_t mask = box_test4<W>(n, 0, r, lo, hi, t_near_out, t_far_out);
  if constexpr (W == 8) mask |= box_test4<W>(n, 4, r, lo, hi, t_near_out, t_far_out) << 4;
  return mask;
}

#include "wide_bvh_filter.inc"

#include "wide_bvh_kernel.inc"

}  // namespace
}  // namespace wide_sse

// ---- AVX2: 8 lanes (4-wide nodes use the SSE box test) ----
#pragma GCC push_options
#pragma GCC target("avx2")
#if defined(__clang__)  // clang ignores `#pragma GCC target`; this is its spelling (the fuzz build uses clang)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#endif
namespace wide_avx2 {
namespace {

struct BoxRay {
  __m256 origin[3], inv_dir[3];
  int near_row[3], far_row[3];
  size_t near_off8[3], far_off8[3];  // the rows' byte offsets in an 8-wide node (a row: 32 bytes)
  float tmin;
  [[gnu::always_inline]] bool prepare(const Ray& ray) {
    const wide_sse::RayVectors v = wide_sse::prepare_vectors(ray);
    wide_sse::BoxRay sse;
    sse.set(v);
    for (int a = 0; a < 3; ++a) {
      origin[a] = _mm256_set_m128(sse.origin[a], sse.origin[a]);
      inv_dir[a] = _mm256_set_m128(sse.inv_dir[a], sse.inv_dir[a]);
      near_row[a] = sse.near_row[a];
      far_row[a] = sse.far_row[a];
      near_off8[a] = size_t(64 * a + 32 * ((v.sign >> a) & 1));
      far_off8[a] = near_off8[a] ^ 32;
    }
    tmin = v.tmin;
    return v.valid;
  }
  // The SSE ray of a 4-wide node: the low halves (no instruction).
  [[gnu::always_inline]] wide_sse::BoxRay sse() const {
    wide_sse::BoxRay s;
    for (int a = 0; a < 3; ++a) {
      s.origin[a] = _mm256_castps256_ps128(origin[a]);
      s.inv_dir[a] = _mm256_castps256_ps128(inv_dir[a]);
      s.near_row[a] = near_row[a];
      s.far_row[a] = far_row[a];
    }
    s.tmin = tmin;
    return s;
  }
};

template <int W>
inline uint32_t box_test(const WideNode<W>& n, const BoxRay& r, float tmin, float tmax, float* t_near_out,
                         float* t_far_out) {
  if constexpr (W == 4) {
    return wide_sse::box_test4<4>(n, 0, r.sse(), _mm_set1_ps(tmin), _mm_set1_ps(tmax), t_near_out, t_far_out);
  } else {
    __m256 t_near = _mm256_set1_ps(-kInfinity), t_far = _mm256_set1_ps(kInfinity);
    for (int a = 0; a < 3; ++a) {
      const char* rows = reinterpret_cast<const char*>(n.box);
      __m256 dn = _mm256_mul_ps(
          _mm256_sub_ps(_mm256_load_ps(reinterpret_cast<const float*>(rows + r.near_off8[a])), r.origin[a]),
          r.inv_dir[a]);
      __m256 df = _mm256_mul_ps(
          _mm256_sub_ps(_mm256_load_ps(reinterpret_cast<const float*>(rows + r.far_off8[a])), r.origin[a]),
          r.inv_dir[a]);
      t_near = _mm256_max_ps(dn, t_near);
      t_far = _mm256_min_ps(df, t_far);
    }
    __m256 t0 = _mm256_max_ps(_mm256_min_ps(_mm256_mul_ps(t_near, _mm256_set1_ps(kDown)),
                                            _mm256_mul_ps(t_near, _mm256_set1_ps(kUp))),
                              _mm256_set1_ps(tmin));
    __m256 t1 = _mm256_min_ps(
        _mm256_max_ps(_mm256_mul_ps(t_far, _mm256_set1_ps(kUp)), _mm256_mul_ps(t_far, _mm256_set1_ps(kDown))),
        _mm256_set1_ps(tmax));
    _mm256_store_ps(t_near_out, t0);
    if (t_far_out) _mm256_store_ps(t_far_out, t1);
    return uint32_t(_mm256_movemask_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ)));
  }
}

#include "wide_bvh_filter.inc"

#include "wide_bvh_kernel.inc"

}  // namespace
}  // namespace wide_avx2
#if defined(__clang__)
#pragma clang attribute pop
#endif
#pragma GCC pop_options

#endif  // __x86_64__

template <class Recorder>
bool WideBvh::traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
  const Impl& m = *impl_;
  bool wide8 = width_ == 8;
  switch (wide_simd_in_use()) {
#if defined(__x86_64__)
    case WideSimd::avx2:
      return wide8 ? wide_avx2::walk<8>(m, ray, hit, any_hit, rec)
                   : wide_avx2::walk<4>(m, ray, hit, any_hit, rec);
    case WideSimd::sse:
      return wide8 ? wide_sse::walk<8>(m, ray, hit, any_hit, rec)
                   : wide_sse::walk<4>(m, ray, hit, any_hit, rec);
#endif
    default:
      return wide8 ? wide_scalar::walk<8>(m, ray, hit, any_hit, rec)
                   : wide_scalar::walk<4>(m, ray, hit, any_hit, rec);
  }
}

bool WideBvh::record(const Ray& ray, Hit* hit, bool any_hit, EventRecorder& rec) const {
  return traverse(ray, hit, any_hit, rec);
}

template bool WideBvh::traverse<NullRecorder>(const Ray&, Hit*, bool, NullRecorder&) const;
template bool WideBvh::traverse<CountingRecorder>(const Ray&, Hit*, bool, CountingRecorder&) const;
template bool WideBvh::traverse<EventRecorder>(const Ray&, Hit*, bool, EventRecorder&) const;

}  // namespace raystep
