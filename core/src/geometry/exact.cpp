#include "raystep/geometry/exact.h"

#include <gmpxx.h>
#include <cmath>

#include "raystep/geometry/numerics.h"

namespace raystep {

namespace {

// Unit roundoff of double, and Shewchuk's bound for a 3x3 determinant whose columns are differences of
// doubles computed with one rounding each: |computed - exact| <= kDetBound * permanent (orient3d's
// errboundA).
constexpr double kU = 0x1p-53;
constexpr double kDetBound = (7.0 + 56.0 * kU) * kU;

struct DetD {
  double value, permanent;
};

// det[x, y, z] = x . (y x z) in double, with its permanent (the same sum of products, in absolute values).
DetD det3(const double x[3], const double y[3], const double z[3]) {
  double m0 = y[1] * z[2] - y[2] * z[1], m1 = y[2] * z[0] - y[0] * z[2], m2 = y[0] * z[1] - y[1] * z[0];
  double p0 = std::fabs(y[1] * z[2]) + std::fabs(y[2] * z[1]);
  double p1 = std::fabs(y[2] * z[0]) + std::fabs(y[0] * z[2]);
  double p2 = std::fabs(y[0] * z[1]) + std::fabs(y[1] * z[0]);
  return {x[0] * m0 + x[1] * m1 + x[2] * m2,
          std::fabs(x[0]) * p0 + std::fabs(x[1]) * p1 + std::fabs(x[2]) * p2};
}

// A value computed with an error of at most `bound` has a known sign: it exceeds the bound, or the bound is
// 0.
bool decided(double value, double bound) {
  return std::fabs(value) > bound || bound == 0.0;
}

// -1, 0 or +1.
template <class T>
int sign_of(const T& v) {
  return (v > 0) - (v < 0);
}

// Exact rationals: p - q for float vectors, and det[x, y, z] = x . (y x z).
void exact_difference(const glm::vec3& p, const glm::vec3& q, mpq_class out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = mpq_class(double(p[i])) - mpq_class(double(q[i]));
}
mpq_class exact_det(const mpq_class x[3], const mpq_class y[3], const mpq_class z[3]) {
  return x[0] * (y[1] * z[2] - y[2] * z[1]) + x[1] * (y[2] * z[0] - y[0] * z[2]) +
         x[2] * (y[0] * z[1] - y[1] * z[0]);
}

// The exact signs of G = N - tmin D and of D, in rational arithmetic (every float is a rational).
void exact_signs(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& o,
                 const glm::vec3& d, float tmin, int* sign_g, int* sign_d) {
  mpq_class a[3], e1[3], e2[3],
      dir[3] = {mpq_class(double(d.x)), mpq_class(double(d.y)), mpq_class(double(d.z))};
  exact_difference(p0, o, a);
  exact_difference(p1, p0, e1);
  exact_difference(p2, p0, e2);
  // N = det[a, e1, e2] = n . a (n = e1 x e2), D = det[d, e1, e2] = n . d.
  mpq_class num = exact_det(a, e1, e2), den = exact_det(dir, e1, e2);
  *sign_g = sgn(num - mpq_class(double(tmin)) * den);
  *sign_d = sgn(den);
}

bool all_finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

int orientation(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& q) {
  if (!(all_finite(p0) && all_finite(p1) && all_finite(p2) && all_finite(q))) return 0;
  double a[3], b[3], c[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = double(p0[i]) - double(q[i]);
    b[i] = double(p1[i]) - double(q[i]);
    c[i] = double(p2[i]) - double(q[i]);
  }
  DetD det = det3(a, b, c);
  if (decided(det.value, kDetBound * det.permanent)) {
    ++exact_counters().filtered;
    return sign_of(det.value);
  }
  ++exact_counters().exact;
  mpq_class x[3], y[3], z[3];
  exact_difference(p0, q, x);
  exact_difference(p1, q, y);
  exact_difference(p2, q, z);
  return sgn(exact_det(x, y, z));
}

void edge_signs(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& o,
                const glm::vec3& d, int signs[3]) {
  if (!(all_finite(p0) && all_finite(p1) && all_finite(p2) && all_finite(o) && all_finite(d))) {
    signs[0] = signs[1] = signs[2] = 0;
    return;
  }
  const glm::vec3* p[3] = {&p0, &p1, &p2};
  double t[3][3], dir[3] = {double(d.x), double(d.y), double(d.z)};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) t[k][i] = double((*p[k])[i]) - double(o[i]);
  for (int e = 0; e < 3; ++e) {
    int j = e == 2 ? 0 : e + 1, k = j == 2 ? 0 : j + 1;
    DetD det = det3(t[j], t[k], dir);
    if (decided(det.value, kDetBound * det.permanent)) {
      ++exact_counters().filtered;
      signs[e] = sign_of(det.value);
    } else {
      ++exact_counters().exact;
      mpq_class x[3], y[3], z[3] = {mpq_class(dir[0]), mpq_class(dir[1]), mpq_class(dir[2])};
      exact_difference(*p[j], o, x);
      exact_difference(*p[k], o, y);
      signs[e] = sgn(exact_det(x, y, z));
    }
  }
}

ExactCounters& exact_counters() {
  thread_local ExactCounters counters;
  return counters;
}

bool plane_hit_beyond(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& o,
                      const glm::vec3& d, float tmin) {
  if (!(all_finite(p0) && all_finite(p1) && all_finite(p2) && all_finite(o) && all_finite(d))) return false;
  if (std::isnan(tmin) || tmin == HUGE_VALF) return false;
  const bool any_tmin = tmin == -HUGE_VALF;  // every t* lies beyond -inf: only D != 0 matters
  const double t0 = any_tmin ? 0.0 : double(tmin);

  // The double filter. N = det[a, b, c] with a = p0 - o, b = p1 - o, c = p2 - o (orient3d of the triangle and
  // the origin); D = det[d, e1, e2] with e1 = p1 - p0, e2 = p2 - p0 (d exact). Each difference of two floats
  // is rounded once in double, as Shewchuk's bound assumes; products of up to three floats neither overflow
  // nor underflow in double.
  double a[3], b[3], c[3], e1[3], e2[3], dir[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = double(p0[i]) - double(o[i]);
    b[i] = double(p1[i]) - double(o[i]);
    c[i] = double(p2[i]) - double(o[i]);
    e1[i] = double(p1[i]) - double(p0[i]);
    e2[i] = double(p2[i]) - double(p0[i]);
    dir[i] = double(d[i]);
  }
  DetD num = det3(a, b, c), den = det3(dir, e1, e2);
  double err_num = kDetBound * num.permanent, err_den = kDetBound * den.permanent;
  // G = N - tmin D: the two errors carried through, plus the product's and the difference's roundings.
  double tden = t0 * den.value;
  double g = num.value - tden;
  double err_g =
      err_num + std::fabs(t0) * err_den + 2.0 * kU * (std::fabs(num.value) + 2.0 * std::fabs(tden));
  err_g *= 1.0 + 4.0 * kU;
  // Decided when the value exceeds its bound, or when the bound is 0: then every product had an exactly zero
  // factor (a difference of two floats is 0 in double only when they are equal, and products of up to three
  // floats never underflow), so the value is exact. That is the common case of an origin on an axis-aligned
  // plane: a shadow ray spawned from a floor at y = 0, whose error bound (and so offset) along y is 0.
  int sign_d = decided(den.value, err_den) ? sign_of(den.value) : 2;  // 2: undecided
  int sign_g = any_tmin ? 0 : (decided(g, err_g) ? sign_of(g) : 2);
  if (sign_d != 2 && sign_g != 2) {
    ++exact_counters().filtered;
    return any_tmin ? sign_d != 0 : sign_g * sign_d > 0;
  }

  // Exact: the float inputs as rationals.
  ++exact_counters().exact;
  int eg, ed;
  exact_signs(p0, p1, p2, o, d, any_tmin ? 0.f : tmin, &eg, &ed);
  if (ed == 0) return false;  // the line is parallel to the plane (or the triangle degenerate)
  if (any_tmin) return true;
  return eg * ed > 0;
}

bool triangle_hit_values(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& o,
                         const glm::vec3& d, const int sign[3], float tmin, float tmax, float* t, float* b0,
                         float* b1, float* b2) {
  // Barycentrics from the three edge determinants, t* = N / D (D is their sum), in double. An edge
  // determinant whose double value disagrees with its exact sign is within its rounding of zero: it counts 0.
  const glm::vec3* p[3] = {&p0, &p1, &p2};
  double v[3][3], dir[3] = {double(d.x), double(d.y), double(d.z)}, edge[3];
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) v[k][i] = double((*p[k])[i]) - double(o[i]);
  double sum = 0.0;
  for (int e = 0; e < 3; ++e) {
    int j = e == 2 ? 0 : e + 1, k = j == 2 ? 0 : j + 1;
    double value = det3(v[j], v[k], dir).value;
    edge[e] = sign_of(value) == sign[e] ? value : 0.0;
    sum += edge[e];
  }
  double n = det3(v[0], v[1], v[2]).value;
  if (sum == 0.0) return false;  // unreachable in exact terms (one sign is nonzero); guards the division
  double t_star = n / sum;
  if (!(t_star < double(tmax))) return false;
  float tf = float(t_star);
  if (!(tf > tmin)) tf = next_float_up(tmin);
  if (!(tf < tmax)) return false;
  *t = tf;
  *b0 = float(edge[0] / sum);
  *b1 = float(edge[1] / sum);
  *b2 = float(edge[2] / sum);
  return true;
}

bool exact_triangle_hit(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& o,
                        const glm::vec3& d, float tmin, float tmax, float* t, float* b0, float* b1,
                        float* b2) {
  int sign[3];
  edge_signs(p0, p1, p2, o, d, sign);
  bool negative =
      sign[0] < 0 || sign[1] < 0 || sign[2]<0, positive = sign[0]> 0 || sign[1] > 0 || sign[2] > 0;
  if (negative == positive) return false;  // outside (mixed signs), or the ray lies in the plane (all zero)
  if (!plane_hit_beyond(p0, p1, p2, o, d, tmin)) return false;
  return triangle_hit_values(p0, p1, p2, o, d, sign, tmin, tmax, t, b0, b1, b2);
}

bool settle_triangle_hit(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& o,
                         const glm::vec3& d, int det_sign, float tmin, float tmax, float* t, float* b0,
                         float* b1, float* b2) {
  // With tmin = 0 (spawned rays testing the surface they leave), t* = N / D > 0 is the side of the plane the
  // origin lies on (orient3d: the sign of N) against the side the ray faces (the sign of D).
  bool beyond =
      tmin == 0.f ? orientation(p0, p1, p2, o) * det_sign > 0 : plane_hit_beyond(p0, p1, p2, o, d, tmin);
  if (!beyond) return false;
  const int sign[3] = {det_sign, det_sign, det_sign};
  return triangle_hit_values(p0, p1, p2, o, d, sign, tmin, tmax, t, b0, b1, b2);
}

}  // namespace raystep
