// Exact answers for the few geometric questions that a floating-point error bound cannot settle. First a
// double-precision filter with a rigorous error bound (Shewchuk, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", 1997: the orient3d bound), then, only when the filter
// cannot decide, exact rational arithmetic on the float inputs (GMP). A conservative bound may send a case
// here; it never turns "cannot prove" into "miss".
#pragma once

#include <glm/vec3.hpp>

namespace raystep {

// The functions are marked cold: the kernels that call them keep their fast paths free of the calls' cost.

// The line o + t d meets the plane of triangle (p0, p1, p2) at t* = N / D, where n = (p1 - p0) x (p2 - p0),
// N = n . (p0 - o) and D = n . d. True when D != 0 and t* > tmin, decided exactly for the float inputs.
// tmin = -inf counts as below every t*; NaN or infinite inputs answer false.
[[gnu::cold]] bool plane_hit_beyond(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                    const glm::vec3& o, const glm::vec3& d, float tmin);

// The exact sign (-1, 0, +1) of det[p0 - q, p1 - q, p2 - q] (orient3d): positive when q lies on the side of
// the plane that n = (p1 - p0) x (p2 - p0) points away from. NaN or infinite inputs give 0.
[[gnu::cold]] int orientation(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                              const glm::vec3& q);

// The exact signs (-1, 0, +1) of det[p_j - o, p_k - o, d] for the edges (j, k) = (1, 2), (2, 0), (0, 1): on
// which side of each edge's line the line o + t d passes. The watertight test's edge functions e0, e1, e2 are
// these determinants divided by d's dominant component. NaN or infinite inputs give 0.
[[gnu::cold]] void edge_signs(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                              const glm::vec3& o, const glm::vec3& d, int signs[3]);

// The whole ray-triangle test for a ray that passes within rounding of an edge's line (or a vertex), where
// the float edge functions cannot be trusted: inside by the exact edge signs (all of one sign, zeros allowed,
// not all zero), tmin < t* decided exactly, t* < tmax in double. On a hit, *t lies in (tmin, tmax) and b0,
// b1, b2
// (>= 0, summing to 1 up to rounding) come from the edge determinants in double.
[[gnu::cold]] bool exact_triangle_hit(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                      const glm::vec3& o, const glm::vec3& d, float tmin, float tmax,
                                      float* t, float* b0, float* b1, float* b2);

// The values of a hit already decided (the ray meets the triangle beyond tmin; sign[i] are the exact edge
// signs, of one sign or zero), in double: t* in (tmin, tmax) as in exact_triangle_hit, and the barycentrics.
// False when t* is not below tmax. For a hit whose float values have a loose bound.
[[gnu::cold]] bool triangle_hit_values(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                       const glm::vec3& o, const glm::vec3& d, const int sign[3], float tmin,
                                       float tmax, float* t, float* b0, float* b1, float* b2);

// A hit whose edges are proven (all of one sign, det_sign: the sign of n . d) but whose t > tmin is not:
// decided exactly (orient3d when tmin = 0, else plane_hit_beyond), then its values as triangle_hit_values
// gives them.
[[gnu::cold]] bool settle_triangle_hit(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                       const glm::vec3& o, const glm::vec3& d, int det_sign, float tmin,
                                       float tmax, float* t, float* b0, float* b1, float* b2);

// How many decisions plane_hit_beyond and edge_signs have settled by its double filter and by exact
// arithmetic, in this thread (tests and benchmarks read them to show how rare the exact path is).
struct ExactCounters {
  unsigned long long filtered = 0, exact = 0;
};
ExactCounters& exact_counters();

}  // namespace raystep
