#include "raystep/scene/flatland.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <glm/common.hpp>

#include "raystep/util/error.h"

namespace raystep {

const char* flat_kind_name(FlatShape::Kind kind) {
  switch (kind) {
    case FlatShape::Kind::segment:
      return "segment";
    case FlatShape::Kind::polyline:
      return "polyline";
    case FlatShape::Kind::polygon:
      return "polygon";
    case FlatShape::Kind::circle:
      return "circle";
  }
  return "";
}

int Flatland::shape_of(uint32_t prim) const {
  auto it = std::upper_bound(shapes.begin(), shapes.end(), prim,
                             [](uint32_t p, const FlatShape& s) { return p < s.first_prim; });
  if (it == shapes.begin()) return -1;
  --it;
  return prim < it->first_prim + it->prim_count ? int(it - shapes.begin()) : -1;
}

void flat_bounds(const std::vector<FlatShape>& shapes, glm::vec2* lo, glm::vec2* hi) {
  *lo = glm::vec2(kInfinity);
  *hi = glm::vec2(-kInfinity);
  for (const FlatShape& s : shapes) {
    if (s.kind == FlatShape::Kind::circle) {
      *lo = glm::min(*lo, s.center - glm::vec2(s.radius));
      *hi = glm::max(*hi, s.center + glm::vec2(s.radius));
    }
    for (const glm::vec2& p : s.points) {
      *lo = glm::min(*lo, p);
      *hi = glm::max(*hi, p);
    }
  }
  if (shapes.empty()) *lo = *hi = glm::vec2(0.f);
}

float flat_half_height(const glm::vec2& lo, const glm::vec2& hi) {
  const float side = std::max(hi.x - lo.x, hi.y - lo.y);
  const float magnitude = std::max({std::fabs(lo.x), std::fabs(lo.y), std::fabs(hi.x), std::fabs(hi.y)});
  return std::max({0.5f * side, 1e-6f * magnitude, 1e-30f});
}

Ray flat_ray(const glm::vec2& origin, const glm::vec2& direction, float tmin, float tmax) {
  Ray r;
  r.origin = glm::vec3(origin, 0.f);
  r.direction = glm::vec3(direction, 0.f);
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

namespace {

// Twice the signed area of the triangle (a, b, c), in double: > 0 counter-clockwise.
double orient(const glm::vec2& a, const glm::vec2& b, const glm::vec2& c) {
  return (double(b.x) - a.x) * (double(c.y) - a.y) - (double(b.y) - a.y) * (double(c.x) - a.x);
}

// Whether segments ab and cd meet (touching counts), by the signs of the orientations.
bool segments_meet(const glm::vec2& a, const glm::vec2& b, const glm::vec2& c, const glm::vec2& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 == 0 && o2 == 0) {  // on one line: do their extents overlap?
    const bool by_x = a.x != b.x;
    const float lo1 = by_x ? std::min(a.x, b.x) : std::min(a.y, b.y),
                hi1 = by_x ? std::max(a.x, b.x) : std::max(a.y, b.y);
    const float lo2 = by_x ? std::min(c.x, d.x) : std::min(c.y, d.y),
                hi2 = by_x ? std::max(c.x, d.x) : std::max(c.y, d.y);
    return lo1 <= hi2 && lo2 <= hi1;
  }
  return ((o1 <= 0 && o2 >= 0) || (o1 >= 0 && o2 <= 0)) && ((o3 <= 0 && o4 >= 0) || (o3 >= 0 && o4 <= 0));
}

// A simple polygon's triangles by ear clipping (small polygons: quadratic is fine). Throws when no ear is
// left, which happens only for a polygon that crosses itself.
std::vector<std::array<size_t, 3>> triangulate(const std::vector<glm::vec2>& p, const std::string& name) {
  std::vector<size_t> left(p.size());
  for (size_t i = 0; i < p.size(); ++i) left[i] = i;
  double area = 0.0;
  for (size_t i = 0; i < p.size(); ++i) area += orient(glm::vec2(0.f), p[i], p[(i + 1) % p.size()]);
  if (area < 0) std::reverse(left.begin(), left.end());  // counter-clockwise from here on
  std::vector<std::array<size_t, 3>> out;
  while (left.size() > 3) {
    bool cut = false;
    for (size_t k = 0; k < left.size() && !cut; ++k) {
      const size_t a = left[(k + left.size() - 1) % left.size()], b = left[k],
                   c = left[(k + 1) % left.size()];
      if (!(orient(p[a], p[b], p[c]) > 0)) continue;  // a reflex or flat corner is no ear
      bool inside = false;
      for (size_t q : left) {
        if (q == a || q == b || q == c) continue;
        if (orient(p[a], p[b], p[q]) >= 0 && orient(p[b], p[c], p[q]) >= 0 && orient(p[c], p[a], p[q]) >= 0)
          inside = true;
      }
      if (inside) continue;
      out.push_back({a, b, c});
      left.erase(left.begin() + std::ptrdiff_t(k));
      cut = true;
    }
    if (!cut) throw InputError("", 0, name + ": the polygon crosses itself (no ear to cut)");
  }
  if (orient(p[left[0]], p[left[1]], p[left[2]]) > 0) out.push_back({left[0], left[1], left[2]});
  return out;
}

// A wall from a to b across z in [-h, h]: two triangles sharing the diagonal.
void add_wall(const glm::vec2& a, const glm::vec2& b, float h, Geometry* g) {
  const glm::vec3 a0(a, -h), b0(b, -h), b1(b, h), a1(a, h);
  g->add_triangle(a0, b0, b1);
  g->add_triangle(a0, b1, a1);
}

}  // namespace

std::string flat_shape_problem(const FlatShape& s) {
  if (s.kind != FlatShape::Kind::polygon || !s.filled) return "";
  const std::vector<glm::vec2>& p = s.points;
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // neighbours share a corner
      if (segments_meet(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]))
        return "the polygon crosses itself (its edges from point " + std::to_string(i) + " and from point " +
               std::to_string(j) + " meet): a filled polygon must be simple";
    }
  return "";
}

void add_flat_shapes(Flatland* flat, Geometry* geometry) {
  flat_bounds(flat->shapes, &flat->lo, &flat->hi);
  const float h = flat->half_height = flat_half_height(flat->lo, flat->hi);
  geometry->set_split_space(SplitSpace{2});  // the structures cut the plane only
  for (FlatShape& s : flat->shapes) {
    s.object = geometry->begin_object(s.name, s.material);
    s.first_prim = uint32_t(geometry->size());
    const std::vector<glm::vec2>& p = s.points;
    switch (s.kind) {
      case FlatShape::Kind::segment:
      case FlatShape::Kind::polyline:
        for (size_t i = 0; i + 1 < p.size(); ++i) add_wall(p[i], p[i + 1], h, geometry);
        break;
      case FlatShape::Kind::polygon:
        for (size_t i = 0; i < p.size(); ++i) add_wall(p[i], p[(i + 1) % p.size()], h, geometry);
        if (s.filled)
          for (const auto& t : triangulate(p, s.name))
            geometry->add_triangle(glm::vec3(p[t[0]], h), glm::vec3(p[t[1]], h), glm::vec3(p[t[2]], h));
        break;
      case FlatShape::Kind::circle: {
        Sphere sphere;
        sphere.center = glm::vec3(s.center, 0.f);
        sphere.radius = s.radius;
        geometry->add_sphere(sphere);
        break;
      }
    }
    s.prim_count = uint32_t(geometry->size()) - s.first_prim;
  }
}

}  // namespace raystep
