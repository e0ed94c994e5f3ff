#include "raystep/geometry/dop.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace raystep {

void fit_slab(const glm::dvec3& n, const std::vector<glm::vec3>& points, const std::vector<Sphere>& spheres,
              double* lo, double* hi) {
  *lo = std::numeric_limits<double>::infinity();
  *hi = -std::numeric_limits<double>::infinity();
  // n . p in double is within gamma(3) sum |n_i p_i| of exact; one more gamma covers the subtraction itself.
  auto extend = [&](const glm::dvec3& p, double reach) {
    const double v = glm::dot(n, p);
    const double e = gamma_double(5) * (std::abs(n.x * p.x) + std::abs(n.y * p.y) + std::abs(n.z * p.z)) +
                     reach * (1.0 + gamma_double(4));
    *lo = std::min(*lo, v - e);
    *hi = std::max(*hi, v + e);
  };
  for (const glm::vec3& p : points) extend(glm::dvec3(p), 0.0);
  for (const Sphere& s : spheres) extend(glm::dvec3(s.center), double(s.radius) * glm::length(n));
}

std::array<glm::dvec3, 3> principal_axes(const std::vector<glm::vec3>& points) {
  glm::dvec3 mean(0.0);
  for (const glm::vec3& p : points) mean += glm::dvec3(p);
  if (!points.empty()) mean /= double(points.size());
  double c[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (const glm::vec3& p : points) {
    const glm::dvec3 v = glm::dvec3(p) - mean;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c[i][j] += v[i] * v[j];
  }
  // Jacobi eigenvalue iteration on the symmetric 3x3 covariance: rotate away the largest off-diagonal entry
  // until none is left; the accumulated rotation's columns are the eigenvectors.
  double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int sweep = 0; sweep < 50; ++sweep) {
    int p = 0, q = 1;
    if (std::abs(c[0][2]) > std::abs(c[p][q])) p = 0, q = 2;
    if (std::abs(c[1][2]) > std::abs(c[p][q])) p = 1, q = 2;
    const double scale = std::abs(c[0][0]) + std::abs(c[1][1]) + std::abs(c[2][2]);
    if (!(std::abs(c[p][q]) > 1e-15 * scale)) break;
    const double theta = (c[q][q] - c[p][p]) / (2.0 * c[p][q]);
    const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
    const double cs = 1.0 / std::sqrt(t * t + 1.0), sn = t * cs;
    for (int k = 0; k < 3; ++k) {  // c = c J
      const double a = c[k][p], b = c[k][q];
      c[k][p] = cs * a - sn * b;
      c[k][q] = sn * a + cs * b;
    }
    for (int k = 0; k < 3; ++k) {  // c = J^T c
      const double a = c[p][k], b = c[q][k];
      c[p][k] = cs * a - sn * b;
      c[q][k] = sn * a + cs * b;
    }
    for (int k = 0; k < 3; ++k) {  // v = v J
      const double a = v[k][p], b = v[k][q];
      v[k][p] = cs * a - sn * b;
      v[k][q] = sn * a + cs * b;
    }
  }
  std::array<glm::dvec3, 3> axes;
  for (int j = 0; j < 3; ++j) axes[j] = glm::normalize(glm::dvec3(v[0][j], v[1][j], v[2][j]));
  return axes;
}

}  // namespace raystep
