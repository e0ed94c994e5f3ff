// The BSP cell's polytope clipping (accel/bsp_cell.h): Sutherland-Hodgman on every face, the cap from the cut
// points sorted by angle around their centroid (a convex polygon's vertices are in angular order).
#include "raystep/accel/bsp_cell.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <glm/geometric.hpp>

namespace raystep {

namespace {

glm::dvec3 area_vector(const glm::dvec3* v, size_t n) {
  glm::dvec3 a(0.0);
  for (size_t i = 0; i < n; ++i) a += glm::cross(v[i], v[(i + 1) % n]);
  return 0.5 * a;
}

// The cut point of the edge (a, b), computed from the endpoints in a fixed order so that the two faces that
// share the edge get the same bits.
glm::dvec3 cut_point(const glm::dvec3& a, double sa, const glm::dvec3& b, double sb) {
  bool swap = std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z);
  const glm::dvec3& p = swap ? b : a;
  const glm::dvec3& q = swap ? a : b;
  double sp = swap ? sb : sa, sq = swap ? sa : sb;
  double t = sp / (sp - sq);  // in (0, 1): sp and sq are of strictly opposite signs
  return p + (q - p) * t;
}

}  // namespace

ConvexCell ConvexCell::box(const Bounds3& b) {
  ConvexCell c;
  if (b.empty()) return c;
  glm::dvec3 lo(b.lo), hi(b.hi);
  auto corner = [&](int i) {
    return glm::dvec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  };
  // Each face by its four corners in cyclic order, then turned to face outward.
  const int faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  const glm::dvec3 centre = 0.5 * (lo + hi);
  c.face_start_.push_back(0);
  for (int f = 0; f < 6; ++f) {
    glm::dvec3 v[4];
    for (int k = 0; k < 4; ++k) v[k] = corner(faces[f][k]);
    int axis = f / 2;
    glm::dvec3 out(0.0);
    out[axis] = (f % 2) ? 1.0 : -1.0;
    glm::dvec3 a = area_vector(v, 4);
    // A flat box's faces have zero area on one axis: orient by the axis instead.
    if (glm::dot(a, out) < 0.0 || (glm::dot(a, out) == 0.0 && glm::dot(v[0] - centre, out) < 0.0))
      std::reverse(v, v + 4);
    for (int k = 0; k < 4; ++k) c.verts_.push_back(v[k]);
    c.face_start_.push_back(uint32_t(c.verts_.size()));
  }
  c.scale_ = std::max(
      {std::fabs(lo.x), std::fabs(lo.y), std::fabs(lo.z), std::fabs(hi.x), std::fabs(hi.y), std::fabs(hi.z)});
  return c;
}

double ConvexCell::area() const {
  double s = 0.0;
  for (size_t f = 0; f < face_count(); ++f) s += glm::length(area_vector(face(f), face_size(f)));
  return s;
}

double ConvexCell::perimeter() const {
  // The top face: the largest upward area vector (the bottom's points down, the sides' are horizontal).
  size_t top = 0;
  double top_z = -kInfinity;
  for (size_t f = 0; f < face_count(); ++f) {
    const double z = area_vector(face(f), face_size(f)).z;
    if (z > top_z) top_z = z, top = f;
  }
  if (empty()) return 0.0;
  double s = 0.0;
  const glm::dvec3* v = face(top);
  const size_t n = face_size(top);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3& a = v[i];
    const glm::dvec3& b = v[(i + 1) % n];
    s += std::hypot(b.x - a.x, b.y - a.y);
  }
  return s;
}

Bounds3 ConvexCell::bounds() const {
  Bounds3 b;
  for (const glm::dvec3& v : verts_) {
    glm::vec3 lo(std::nextafter(float(v.x), -kInfinity), std::nextafter(float(v.y), -kInfinity),
                 std::nextafter(float(v.z), -kInfinity));
    glm::vec3 hi(std::nextafter(float(v.x), kInfinity), std::nextafter(float(v.y), kInfinity),
                 std::nextafter(float(v.z), kInfinity));
    b.extend(lo);
    b.extend(hi);
  }
  return b;
}

void ConvexCell::extent(const glm::dvec3& n, double* lo, double* hi) const {
  double a = kInfinity, b = -kInfinity;
  for (const glm::dvec3& v : verts_) {
    double s = glm::dot(n, v);
    a = std::min(a, s);
    b = std::max(b, s);
  }
  *lo = a;
  *hi = b;
}

double ConvexCell::tolerance(const glm::dvec3& n, double d) const {
  // 2^-40 of the coordinates' scale: far above the rounding of a dot product (2^-52), far below any feature
  // a float scene can have (2^-23).
  double len = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
  return std::ldexp(scale_ * len + std::fabs(d), -40);
}

void ConvexCell::split(const glm::dvec3& n, double d, ConvexCell* below, ConvexCell* above) const {
  *below = ConvexCell();
  *above = ConvexCell();
  if (empty()) return;
  const double tol = tolerance(n, d);
  std::vector<glm::dvec3> cap;
  ConvexCell* parts[2] = {below, above};
  for (ConvexCell* p : parts) {
    p->face_start_.assign(1, 0);
    p->scale_ = scale_;
  }
  std::vector<double> side;
  bool any_below = false, any_above = false;
  for (size_t f = 0; f < face_count(); ++f) {
    const glm::dvec3* v = face(f);
    const size_t m = face_size(f);
    side.resize(m);
    for (size_t i = 0; i < m; ++i) {
      double s = glm::dot(n, v[i]) - d;
      side[i] = std::fabs(s) <= tol ? 0.0 : s;
      if (side[i] == 0.0) cap.push_back(v[i]);
      any_below |= side[i] < 0.0;
      any_above |= side[i] > 0.0;
    }
    for (int part = 0; part < 2; ++part) {
      ConvexCell& out = *parts[part];
      const double sign = part == 0 ? -1.0 : 1.0;  // the part keeps the vertices with sign * s >= 0
      const size_t start = out.verts_.size();
      for (size_t i = 0; i < m; ++i) {
        size_t j = (i + 1) % m;
        double si = side[i] * sign, sj = side[j] * sign;
        if (si >= 0.0) out.verts_.push_back(v[i]);
        if ((si > 0.0 && sj < 0.0) || (si < 0.0 && sj > 0.0)) {
          glm::dvec3 c = cut_point(v[i], side[i], v[j], side[j]);
          out.verts_.push_back(c);
          if (part == 0) cap.push_back(c);
        }
      }
      if (out.verts_.size() - start < 3)
        out.verts_.resize(start);  // the face only touches the plane from the other side
      else
        out.face_start_.push_back(uint32_t(out.verts_.size()));
    }
  }
  if (!any_below || !any_above) {
    // The plane does not cut the cell (within the tolerance): the cell is whole on its side (below, if it
    // lies in the plane), the other part empty.
    *below = any_above ? ConvexCell() : *this;
    *above = any_above ? *this : ConvexCell();
    return;
  }
  // The cap: the cut points and on-plane vertices, deduplicated, by angle around their centroid.
  std::sort(cap.begin(), cap.end(), [](const glm::dvec3& a, const glm::dvec3& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  });
  cap.erase(std::unique(cap.begin(), cap.end()), cap.end());
  if (cap.size() < 3) return;
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& p : cap) centre += p;
  centre /= double(cap.size());
  glm::dvec3 u =
      std::fabs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0)) : glm::cross(n, glm::dvec3(0, 1, 0));
  u = glm::normalize(u);
  glm::dvec3 w = glm::cross(n, u);  // (u, w, n) right-handed: counter-clockwise in (u, w) faces +n
  std::vector<std::pair<double, glm::dvec3>> ordered;
  ordered.reserve(cap.size());
  for (const glm::dvec3& p : cap)
    ordered.emplace_back(std::atan2(glm::dot(p - centre, w), glm::dot(p - centre, u)), p);
  std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  // Below's cap faces +n (outward, counter-clockwise); above's faces -n (reversed).
  for (const auto& e : ordered) below->verts_.push_back(e.second);
  below->face_start_.push_back(uint32_t(below->verts_.size()));
  for (auto it = ordered.rbegin(); it != ordered.rend(); ++it) above->verts_.push_back(it->second);
  above->face_start_.push_back(uint32_t(above->verts_.size()));
}

void ConvexCell::split_areas(const glm::dvec3& n, double d, double* below, double* above) const {
  *below = *above = 0.0;
  if (empty()) return;
  const double tol = tolerance(n, d);
  glm::dvec3 sum_below(0.0), sum_above(0.0);  // the faces' area vectors: the cap closes each sum to zero
  double area_below = 0.0, area_above = 0.0;
  bool any_below = false, any_above = false;
  for (size_t f = 0; f < face_count(); ++f) {
    const glm::dvec3* v = face(f);
    const size_t m = face_size(f);
    // Area vectors of the clipped polygons, as 0.5 * sum of cross(p_k, p_k+1) over their vertices in order.
    glm::dvec3 ab(0.0), aa(0.0);
    glm::dvec3 first_b(0.0), prev_b(0.0), first_a(0.0), prev_a(0.0);
    int nb = 0, na = 0;
    auto emit = [](glm::dvec3& acc, glm::dvec3& first, glm::dvec3& prev, int& count, const glm::dvec3& p) {
      if (count == 0)
        first = p;
      else
        acc += glm::cross(prev, p);
      prev = p;
      ++count;
    };
    double s_prev = glm::dot(n, v[m - 1]) - d;
    if (std::fabs(s_prev) <= tol) s_prev = 0.0;
    for (size_t i = 0; i < m; ++i) {
      // Edge (v[i-1], v[i]): emit the cut point, then v[i] to the parts that keep it.
      const glm::dvec3& p = v[i];
      const glm::dvec3& q = v[(i + m - 1) % m];
      double s = glm::dot(n, p) - d;
      if (std::fabs(s) <= tol) s = 0.0;
      if ((s_prev < 0.0 && s > 0.0) || (s_prev > 0.0 && s < 0.0)) {
        glm::dvec3 c = cut_point(q, s_prev, p, s);
        emit(ab, first_b, prev_b, nb, c);
        emit(aa, first_a, prev_a, na, c);
      }
      if (s <= 0.0) emit(ab, first_b, prev_b, nb, p);
      if (s >= 0.0) emit(aa, first_a, prev_a, na, p);
      any_below |= s < 0.0;
      any_above |= s > 0.0;
      s_prev = s;
    }
    if (nb >= 3) {
      ab += glm::cross(prev_b, first_b);
      sum_below += 0.5 * ab;
      area_below += 0.5 * glm::length(ab);
    }
    if (na >= 3) {
      aa += glm::cross(prev_a, first_a);
      sum_above += 0.5 * aa;
      area_above += 0.5 * glm::length(aa);
    }
  }
  if (!any_below || !any_above) {
    // Not cut: the whole cell is on one side.
    double whole = area();
    *below = any_below ? whole : 0.0;
    *above = any_below ? 0.0 : whole;
    return;
  }
  *below = area_below + glm::length(sum_below);
  *above = area_above + glm::length(sum_above);
}

void ConvexCell::split_measures(const glm::dvec3& n, double d, SplitSpace space, double* below,
                                double* above) const {
  if (!space.plane()) return split_areas(n, d, below, above);
  ConvexCell b, a;
  split(n, d, &b, &a);
  *below = b.perimeter();
  *above = a.perimeter();
}

}  // namespace raystep
