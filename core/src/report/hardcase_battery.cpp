#include "raystep/report/hardcase_battery.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include <glm/geometric.hpp>

#include "raystep/geometry/icosphere.h"
#include "raystep/geometry/numerics.h"
#include "raystep/report/hardcase_reference.h"
#include "raystep/scene/ray_sets.h"

namespace raystep {
namespace {

using glm::dvec3;
using glm::vec3;

// std::mt19937_64's sequence is fixed by the standard; the conversions are ours (as in ray_sets.cpp).
struct Rng {
  std::mt19937_64 engine;
  explicit Rng(uint64_t seed) : engine(seed) {}
  uint64_t below(uint64_t n) { return engine() % n; }
};

Geometry to_geometry(const TriangleMesh& mesh, const std::string& name) {
  Geometry g;
  g.begin_object(name, 0);
  for (const glm::uvec3& t : mesh.triangles)
    g.add_triangle(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
  return g;
}

void add_ray(HardCaseSet& set, const vec3& origin, const vec3& direction, bool must_hit,
             const vec3& target = vec3(std::nanf(""))) {
  Ray r;
  r.origin = origin;
  r.direction = direction;
  set.rays.push_back(r);
  set.must_hit.push_back(must_hit);
  set.targets.push_back(target);
}

// ---- Built-in meshes ----

TriangleMesh octahedron() {
  TriangleMesh m;
  m.positions = {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1)};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

// The cube [lo, hi]^3 with n x n quads per face, vertices shared (indexed), wound outwards.
TriangleMesh subdivided_cube(int n, float lo, float hi) {
  TriangleMesh m;
  std::map<std::array<int, 3>, uint32_t> index;
  auto vertex = [&](std::array<int, 3> g) {
    auto [it, fresh] = index.emplace(g, uint32_t(m.positions.size()));
    if (fresh) {
      vec3 p;
      for (int a = 0; a < 3; ++a)
        p[a] = g[a] == 0 ? lo : g[a] == n ? hi : lo + (hi - lo) * float(g[a]) / float(n);
      m.positions.push_back(p);
    }
    return it->second;
  };
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          uint32_t q[4];
          const int corner[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          for (int k = 0; k < 4; ++k) {
            std::array<int, 3> g;
            g[a] = side * n, g[u] = corner[k][0], g[v] = corner[k][1];
            q[k] = vertex(g);
          }
          if (side == 1) {  // u x v = +a: counter-clockwise seen from outside
            m.triangles.push_back({q[0], q[1], q[2]});
            m.triangles.push_back({q[0], q[2], q[3]});
          } else {
            m.triangles.push_back({q[0], q[2], q[1]});
            m.triangles.push_back({q[0], q[3], q[2]});
          }
        }
    }
  return m;
}

TriangleMesh torus(int major, int minor, float r_major, float r_minor) {
  TriangleMesh m;
  for (int i = 0; i < major; ++i)
    for (int j = 0; j < minor; ++j) {
      double u = 2 * M_PI * i / major, v = 2 * M_PI * j / minor;
      double r = r_major + r_minor * std::cos(v);
      m.positions.push_back(
          vec3(float(r * std::cos(u)), float(r * std::sin(u)), float(r_minor * std::sin(v))));
    }
  auto id = [&](int i, int j) { return uint32_t((i % major) * minor + (j % minor)); };
  for (int i = 0; i < major; ++i)
    for (int j = 0; j < minor; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

// A closed bipyramid: a regular n-gon of the given radius in z = 0, apexes at z = +-half_height.
TriangleMesh bipyramid(int n, float radius, float half_height) {
  TriangleMesh m;
  for (int i = 0; i < n; ++i) {
    double a = 2 * M_PI * i / n;
    m.positions.push_back(vec3(float(radius * std::cos(a)), float(radius * std::sin(a)), 0.f));
  }
  m.positions.push_back(vec3(0, 0, half_height));
  m.positions.push_back(vec3(0, 0, -half_height));
  const uint32_t top = uint32_t(n), bottom = uint32_t(n + 1);
  for (int i = 0; i < n; ++i) {
    uint32_t a = uint32_t(i), b = uint32_t((i + 1) % n);
    m.triangles.push_back({a, b, top});
    m.triangles.push_back({b, a, bottom});
  }
  return m;
}

// A flat tetrahedron whose apex d lies 1e-3 above the middle of edge ab: face (a, b, d) is a cap (an angle of
// nearly 180 degrees at d), the others are long and flat.
TriangleMesh cap_tetrahedron() {
  TriangleMesh m;
  m.positions = {vec3(-1, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1e-3f)};
  m.triangles = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 2, 1}};
  return m;
}

// The octahedron with a T-junction closed by a zero-area (collinear) triangle, and triangles with repeated
// vertices: every edge is still used an even number of times, and no degenerate triangle may ever be hit.
TriangleMesh octahedron_with_degenerates() {
  TriangleMesh m = octahedron();
  const uint32_t mid = uint32_t(m.positions.size());
  m.positions.push_back(vec3(0.5f, 0.5f, 0.f));  // exactly on edge (+x, +y)
  m.triangles[0] = {0, mid, 4};                  // face (+x, +y, +z) split at the midpoint of its edge...
  m.triangles.push_back({mid, 2, 4});
  m.triangles.push_back({0, 2, mid});  // ...and the collinear triangle that closes the T-junction
  m.triangles.push_back({4, 4, 1});    // a repeated vertex: a segment
  m.triangles.push_back({5, 5, 5});    // a point
  return m;
}

TriangleMesh from_indexed(const IndexedMesh& im) {
  TriangleMesh m;
  m.positions = im.positions;
  m.triangles = im.triangles;
  return m;
}

// Two directions for the parity test, far from any axis or diagonal.
const vec3 kParityDirections[2] = {vec3(0.5773503f, 0.6123724f, 0.5400617f),
                                   vec3(-0.4123f, 0.7312f, -0.5431f)};

bool inside_by_parity(const TriangleMesh& mesh, const vec3& p) {
  for (const vec3& d : kParityDirections) {
    Ray r;
    r.origin = p;
    r.direction = d;
    if (crossing_parity(mesh.positions, mesh.triangles, r) != 1) return false;
  }
  return true;
}

vec3 edge_point(const vec3& a, const vec3& b, int k) {
  return a + (float(k) / 16.f) * (b - a);
}

// A vertex (even draws) or an edge point (odd draws) of a random triangle.
vec3 random_feature(const TriangleMesh& mesh, Rng& rng) {
  const glm::uvec3& t = mesh.triangles[rng.below(mesh.triangles.size())];
  const int k = int(rng.below(3));
  if (rng.below(2) == 0) return mesh.positions[t[k]];
  return edge_point(mesh.positions[t[k]], mesh.positions[t[(k + 1) % 3]], 1 + int(rng.below(15)));
}

std::string scaled_name(const std::string& mesh, int scale) {
  return mesh + " " + hardcase_scale_name(scale);
}

size_t auto_rays(const HardCaseOptions& o, size_t triangles, int sets) {
  if (o.mesh_rays > 0) return o.mesh_rays;
  size_t n = size_t(o.reference_budget / std::max<uint64_t>(1, uint64_t(triangles) * uint64_t(sets)));
  return std::clamp<size_t>(n, 64, 2048);
}

// ---- The families on built-in geometry ----

// Axis-parallel rays along a subdivided cube's edges, face diagonals and face-centre lines, with +0 and -0
// transverse components, at transverse offsets on, just inside and just outside the faces.
HardCaseSet axis_set(float s) {
  HardCaseSet set;
  set.family = HardCaseFamily::axis;
  char name[64];
  std::snprintf(name, sizeof name, "cube 2x2 per face x%g", double(s));
  set.name = name;
  const TriangleMesh cube = subdivided_cube(2, -s, s);
  set.geometry = to_geometry(cube, set.name);
  const float offsets[] = {-s, -0.f, 0.f, 0.5f * s, s, next_float_up(s), next_float_down(s)};
  for (int a = 0; a < 3; ++a)
    for (float sign : {1.f, -1.f})
      for (float u : offsets)
        for (float v : offsets)
          for (int zeros = 0; zeros < 4; ++zeros)
            for (bool from_inside : {false, true}) {
              vec3 o, d;
              const int ua = (a + 1) % 3, va = (a + 2) % 3;
              o[a] = from_inside ? 0.f : -3.f * s * sign;
              o[ua] = u, o[va] = v;
              d[a] = sign;
              d[ua] = (zeros & 1) ? -0.f : 0.f;
              d[va] = (zeros & 2) ? -0.f : 0.f;
              add_ray(set, o, d, std::fabs(u) <= s && std::fabs(v) <= s);
            }
  return set;
}

// A tessellated plane of 8 x 8 unit quads over [-4, 4]^2 (diagonals alternating), placed by `place`
// (local point -> world point), hit through its vertices and edge points from above and below, straight
// and slanted, and grazed in its own plane.
template <class Place>
HardCaseSet plane_set(const std::string& name, Place place, bool axis_aligned) {
  HardCaseSet set;
  set.family = HardCaseFamily::plane;
  set.name = name;
  TriangleMesh m;
  const int n = 8;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.push_back(place(vec3(float(i - 4), float(j - 4), 0.f)));
  auto id = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        m.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  set.geometry = to_geometry(m, name);
  // Targets in local coordinates: every vertex, and points k/16 along every edge of the first diagonal's
  // orientation and the grid lines.
  std::vector<vec3> local;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      local.push_back(vec3(float(i - 4), float(j - 4), 0.f));
      for (int k : {1, 8, 15}) {
        const float f = float(k) / 16.f;
        if (i < n) local.push_back(vec3(float(i - 4) + f, float(j - 4), 0.f));
        if (j < n) local.push_back(vec3(float(i - 4), float(j - 4) + f, 0.f));
        if (i < n && j < n) {
          if ((i + j) % 2 == 0)
            local.push_back(vec3(float(i - 4) + f, float(j - 4) + f, 0.f));
          else
            local.push_back(vec3(float(i - 4) + 1.f - f, float(j - 4) + f, 0.f));
        }
      }
    }
  const vec3 offsets[] = {vec3(0, 0, 3), vec3(0, 0, -3), vec3(1, 2, 3), vec3(-2.5f, 0.5f, -1.5f)};
  int count = 0;
  for (const vec3& l : local) {
    const bool interior = std::fabs(l.x) < 4.f && std::fabs(l.y) < 4.f;
    const vec3 target = place(l);
    for (const vec3& off : offsets) {
      const vec3 origin = place(l + off);
      vec3 d = target - origin;
      if (axis_aligned && off.x == 0.f && (count++ % 2)) d.x = -0.f, d.y = -0.f;  // -0 and +0 alike
      add_ray(set, origin, d, interior, target);
    }
  }
  // Grazing: rays in the plane itself, along grid lines, through vertices and along a diagonal.
  for (float y : {-4.f, -3.f, -2.5f, 0.f, 1.f, 3.5f, 4.f}) {
    const vec3 o = place(vec3(-6.f, y, 0.f));
    add_ray(set, o, place(vec3(6.f, y, 0.f)) - o, false);
  }
  const vec3 o = place(vec3(-6.f, -6.f, 0.f));
  add_ray(set, o, place(vec3(6.f, 6.f, 0.f)) - o, false);
  return set;
}

// Identical triangles (the same, reversed, rotated), coplanar overlapping ones and a larger one around them,
// in a plane placed by `place`; small triangles elsewhere so that the trees split. Rays at the triangle's
// centre (must hit), vertices and edge points from both sides.
template <class Place>
HardCaseSet overlap_set(const std::string& name, Place place) {
  HardCaseSet set;
  set.family = HardCaseFamily::overlap;
  set.name = name;
  Geometry& g = set.geometry;
  g.begin_object(name, 0);
  const vec3 a = place(vec3(0, 0, 0)), b = place(vec3(2, 0, 0)), c = place(vec3(0.5f, 1.5f, 0));
  g.add_triangle(a, b, c);
  g.add_triangle(a, b, c);                                                                 // duplicated
  g.add_triangle(a, c, b);                                                                 // reversed
  g.add_triangle(b, c, a);                                                                 // rotated
  g.add_triangle(place(vec3(1, 0, 0)), place(vec3(3, 0.5f, 0)), place(vec3(1.5f, 2, 0)));  // overlapping
  g.add_triangle(place(vec3(-2, -1, 0)), place(vec3(5, -1, 0)), place(vec3(0.5f, 5, 0)));  // around them
  Rng rng(7);
  for (int k = 0; k < 40; ++k) {
    const vec3 p(float(rng.below(100)) * 0.1f - 5.f, float(rng.below(100)) * 0.1f - 5.f, 2.f + float(k % 5));
    g.add_triangle(place(p), place(p + vec3(0.3f, 0, 0.1f)), place(p + vec3(0, 0.3f, -0.1f)));
  }
  std::vector<std::pair<vec3, bool>> local = {{vec3(2.5f / 3, 0.5f, 0), true}, {vec3(0, 0, 0), false},
                                              {vec3(2, 0, 0), false},          {vec3(0.5f, 1.5f, 0), false},
                                              {vec3(1, 0, 0), false},          {vec3(1.5f, 2, 0), false}};
  for (int k : {1, 4, 8, 13})
    for (int e = 0; e < 3; ++e) {
      const vec3 p[3] = {vec3(0, 0, 0), vec3(2, 0, 0), vec3(0.5f, 1.5f, 0)};
      local.push_back({edge_point(p[e], p[(e + 1) % 3], k), false});
    }
  const vec3 offsets[] = {vec3(0, 0, 2), vec3(0, 0, -2), vec3(0.7f, -0.4f, 1.1f), vec3(-0.3f, 0.9f, -1.7f)};
  for (const auto& [l, must] : local)
    for (const vec3& off : offsets) {
      const vec3 target = place(l), origin = place(l + off);
      add_ray(set, origin, target - origin, must,
              must ? vec3(std::nanf("")) : target);  // the centre: no edge
    }
  return set;
}

// A disc of 256 needle triangles around one vertex in z = 0: rays through the centre, where 256 slivers meet,
// and through points on the needles' edges.
HardCaseSet needle_fan_set() {
  HardCaseSet set;
  set.family = HardCaseFamily::sliver;
  set.name = "needle fan, 256 triangles";
  Geometry& g = set.geometry;
  g.begin_object(set.name, 0);
  const int n = 256;
  std::vector<vec3> rim;
  for (int i = 0; i < n; ++i) {
    double a = 2 * M_PI * i / n;
    rim.push_back(vec3(float(10 * std::cos(a)), float(10 * std::sin(a)), 0.f));
  }
  const vec3 centre(0.f);
  for (int i = 0; i < n; ++i) g.add_triangle(centre, rim[i], rim[(i + 1) % n]);
  const vec3 offsets[] = {vec3(0, 0, 1), vec3(0, 0, -1), vec3(0.3f, 0.1f, 1), vec3(-0.02f, 0.05f, -1)};
  for (int i = 0; i < n; i += 3)
    for (int k : {0, 1, 2, 8}) {
      const vec3 target = k == 0 ? centre : edge_point(centre, rim[i], k);
      for (const vec3& off : offsets) add_ray(set, target + off, -off, true, target);
    }
  return set;
}

// NaN, infinite, zero, tiny and huge rays at a geometry whose interior holds `inside` (a closed mesh) or
// without an interior point (nullptr). `aimed` are finite rays at the geometry, each of which must hit when
// `inside` is given.
void add_nonfinite_rays(HardCaseSet& set, const std::vector<Ray>& aimed, bool aimed_must_hit) {
  const float nan = std::nanf(""), inf = kInfinity;
  for (size_t i = 0; i < aimed.size(); ++i) {
    const Ray& r = aimed[i];
    // Direction lengths 1e-30 and 1e30 (and the plain one): the same hit, at t scaled by 1e30 and 1e-30.
    for (float scale : {1.f, 1e-30f, 1e30f}) add_ray(set, r.origin, r.direction * scale, aimed_must_hit);
    // NaN or infinite in one component of the origin or of the direction.
    const int a = int(i % 3);
    for (float bad : {nan, inf, -inf}) {
      vec3 o = r.origin, d = r.direction;
      o[a] = bad;
      add_ray(set, o, r.direction, false);
      d[a] = bad;
      add_ray(set, r.origin, d, false);
    }
    add_ray(set, r.origin, vec3(0.f), false);   // no direction
    add_ray(set, r.origin, vec3(-0.f), false);  // no direction, signed
    // NaN and infinite bounds: a NaN bound meets nothing, nor does an empty interval.
    for (auto [tmin, tmax] :
         {std::pair{nan, inf}, std::pair{0.f, nan}, std::pair{inf, inf}, std::pair{0.f, 0.f}}) {
      add_ray(set, r.origin, r.direction, false);
      set.rays.back().tmin = tmin;
      set.rays.back().tmax = tmax;
    }
  }
}

// The nonfinite rays at the user's mesh: variants of the first rays of its inside family at x1 (battery[1]),
// or of its surface family (battery[0]) when it is not closed.
void append_mesh_nonfinite(std::vector<HardCaseSet>& battery, bool open_mesh) {
  const HardCaseSet& source = open_mesh ? battery[0] : battery[1];
  HardCaseSet set;
  set.family = HardCaseFamily::nonfinite;
  set.name = "mesh";
  set.geometry = source.geometry;
  set.same_geometry_as = open_mesh ? 0 : 1;
  std::vector<Ray> aimed(source.rays.begin(), source.rays.begin() + std::min<size_t>(32, source.rays.size()));
  add_nonfinite_rays(set, aimed, !open_mesh);
  battery.push_back(std::move(set));
}

}  // namespace

const char* hardcase_family_name(HardCaseFamily family) {
  switch (family) {
    case HardCaseFamily::inside:
      return "inside";
    case HardCaseFamily::surface:
      return "surface";
    case HardCaseFamily::axis:
      return "axis";
    case HardCaseFamily::plane:
      return "plane";
    case HardCaseFamily::overlap:
      return "overlap";
    case HardCaseFamily::sliver:
      return "sliver";
    case HardCaseFamily::nonfinite:
      return "nonfinite";
  }
  return "?";
}

MeshClosure mesh_closure(const TriangleMesh& mesh) {
  std::vector<std::array<uint32_t, 6>> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const glm::uvec3& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      std::array<uint32_t, 3> a, b;
      for (int c = 0; c < 3; ++c) {
        a[c] = float_to_bits(mesh.positions[t[k]][c] + 0.f);  // +0.f: -0 and +0 are one position
        b[c] = float_to_bits(mesh.positions[t[(k + 1) % 3]][c] + 0.f);
      }
      if (a == b) continue;  // a repeated vertex: no edge
      if (b < a) std::swap(a, b);
      edges.push_back({a[0], a[1], a[2], b[0], b[1], b[2]});
    }
  std::sort(edges.begin(), edges.end());
  MeshClosure c;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    ++c.edges;
    c.odd_edges += (j - i) % 2;
    i = j;
  }
  return c;
}

std::string hardcase_scale_name(int scale) {
  switch (scale) {
    case 0:
      return "x1e-6";
    case 1:
      return "x1";
    case 2:
      return "x1e6";
    default:
      return "x1 moved 1000 extents";
  }
}

std::vector<vec3> hardcase_scaled(const std::vector<vec3>& positions, int scale) {
  std::vector<vec3> out = positions;
  if (scale == 0 || scale == 2) {
    const float s = scale == 0 ? 1e-6f : 1e6f;
    for (vec3& p : out) p *= s;
  } else if (scale == 3) {
    Bounds3 b;
    for (const vec3& p : positions) b.extend(p);
    const float extent = std::max({b.extent().x, b.extent().y, b.extent().z});
    const vec3 shift = 1000.f * extent * vec3(1.f, -0.75f, 0.5f);
    for (vec3& p : out) p += shift;
  }
  return out;
}

HardCaseSet inside_rays_set(const TriangleMesh& mesh, const std::string& name, HardCaseFamily family,
                            size_t rays, uint64_t seed) {
  HardCaseSet set;
  set.family = family;
  set.name = name;
  set.geometry = to_geometry(mesh, name);
  if (mesh.triangles.empty()) return set;
  Rng rng(seed);
  const size_t points = (rays + 7) / 8;
  for (size_t attempt = 0, found = 0; found < points && attempt < 4 * points + 16; ++attempt) {
    const glm::uvec3& tri = mesh.triangles[rng.below(mesh.triangles.size())];
    const vec3 &p0 = mesh.positions[tri[0]], &p1 = mesh.positions[tri[1]], &p2 = mesh.positions[tri[2]];
    const dvec3 q0(p0), q1(p1), q2(p2);
    const dvec3 n = glm::cross(q1 - q0, q2 - q0);
    const double area2 = glm::length(n);
    const double longest = std::max({glm::length(q1 - q0), glm::length(q2 - q1), glm::length(q0 - q2)});
    if (!(area2 > 0.0)) continue;  // degenerate: no inside next to it
    // A point just inside the triangle: a twentieth of its smallest altitude off its centroid, on the side
    // the parity of crossings says is inside (an outward winding puts it at -n).
    const double h = 0.05 * area2 / longest;
    const dvec3 centroid = (q0 + q1 + q2) / 3.0;
    vec3 p;
    bool ok = false;
    for (double side : {-1.0, 1.0}) {
      p = vec3(centroid + side * h * (n / area2));
      if (inside_by_parity(mesh, p)) {
        ok = true;
        break;
      }
    }
    if (!ok) continue;
    ++found;
    // The triangle's own vertices and edge points, seen through its boundary at once; then features
    // elsewhere.
    vec3 targets[8] = {p0,
                       p1,
                       p2,
                       edge_point(p0, p1, 1 + int(rng.below(15))),
                       edge_point(p1, p2, 1 + int(rng.below(15))),
                       edge_point(p2, p0, 1 + int(rng.below(15))),
                       random_feature(mesh, rng),
                       random_feature(mesh, rng)};
    for (const vec3& t : targets) add_ray(set, p, t - p, true, t);
  }
  return set;
}

std::vector<HardCaseSet> hardcase_battery(const TriangleMesh* mesh, const HardCaseOptions& options,
                                          std::string* note) {
  std::vector<HardCaseSet> battery;
  std::string notes;
  // inside: the user's closed mesh, or the built-in ones, at four scales.
  std::vector<std::pair<std::string, TriangleMesh>> closed;
  if (mesh) {
    MeshClosure c = mesh_closure(*mesh);
    if (c.closed()) {
      closed.push_back({"mesh", *mesh});
    } else {
      notes +=
          "the mesh is not closed (" + std::to_string(c.odd_edges) + " of its " + std::to_string(c.edges) +
          " edges are used by an odd number of triangles; closed means every edge, keyed by its end points' "
          "coordinates, is shared by an even number): the inside family is skipped. ";
    }
  } else {
    closed.push_back({"octahedron", octahedron()});
    closed.push_back({"cube 4x4 per face", subdivided_cube(4, -1.f, 1.f)});
    closed.push_back({"icosphere 3", from_indexed(make_icosphere(3))});
    closed.push_back({"torus 32x12", torus(32, 12, 1.f, 0.3f)});
  }
  for (const auto& [name, m] : closed) {
    const size_t rays = auto_rays(options, m.triangles.size(), kHardCaseScales);
    for (int s = 0; s < kHardCaseScales; ++s) {
      TriangleMesh scaled = m;
      scaled.positions = hardcase_scaled(m.positions, s);
      battery.push_back(inside_rays_set(scaled, scaled_name(name, s), HardCaseFamily::inside, rays,
                                        options.seed + uint64_t(s)));
    }
  }
  // surface: the user's mesh from outside, aimed at its edges and vertices.
  if (mesh && !mesh->triangles.empty()) {
    HardCaseSet set;
    set.family = HardCaseFamily::surface;
    set.name = "mesh from outside";
    set.geometry = to_geometry(*mesh, set.name);
    const size_t rays = auto_rays(options, mesh->triangles.size(), 1);
    std::vector<vec3> targets = edge_targets(set.geometry, rays, options.seed);
    std::vector<Ray> aimed = edge_rays(set.geometry, rays, options.seed);
    for (size_t i = 0; i < aimed.size(); ++i)
      add_ray(set, aimed[i].origin, aimed[i].direction, false, targets[i]);
    battery.push_back(std::move(set));
  }
  if (mesh && !options.built_in_families) {
    append_mesh_nonfinite(battery, closed.empty());
    if (note) *note = notes;
    return battery;
  }
  // axis: the cube at three scales.
  for (float s : {1e-6f, 1.f, 1e6f}) battery.push_back(axis_set(s));
  // plane: axis-aligned at three scales, and tilted.
  for (float s : {1e-6f, 1.f, 1e6f}) {
    char name[64];
    std::snprintf(name, sizeof name, "plane 8x8 x%g", double(s));
    battery.push_back(plane_set(
        name, [s](const vec3& p) { return p * s; }, true));
  }
  const glm::dmat3 tilt = [] {
    const dvec3 axis = glm::normalize(dvec3(1, 2, 3));
    const double a = 0.7, c = std::cos(a), s = std::sin(a);
    glm::dmat3 k(0, axis.z, -axis.y, -axis.z, 0, axis.x, axis.y, -axis.x, 0);  // columns
    return glm::dmat3(1.0) + s * k + (1 - c) * k * k;
  }();
  auto tilted = [tilt](const vec3& p) { return vec3(tilt * dvec3(p) + dvec3(0.25, -0.5, 3.0)); };
  battery.push_back(plane_set("plane 8x8 tilted", tilted, false));
  // overlap: in z = 1 and tilted.
  battery.push_back(
      overlap_set("coincident and coplanar, z = 1", [](const vec3& p) { return p + vec3(0, 0, 1); }));
  battery.push_back(overlap_set("coincident and coplanar, tilted", tilted));
  // sliver: closed meshes of needles, a cap and zero-area triangles; a fan of needles.
  battery.push_back(inside_rays_set(bipyramid(64, 1.f, 1e4f), "needle bipyramid, 64 sides, aspect 1e4",
                                    HardCaseFamily::sliver, 512, options.seed));
  battery.push_back(inside_rays_set(cap_tetrahedron(), "cap tetrahedron, apex 1e-3 off its edge",
                                    HardCaseFamily::sliver, 256, options.seed));
  battery.push_back(inside_rays_set(octahedron_with_degenerates(),
                                    "octahedron with zero-area and repeated-vertex triangles",
                                    HardCaseFamily::sliver, 512, options.seed));
  battery.push_back(needle_fan_set());
  // nonfinite: from inside the octahedron, and at the user's mesh.
  {
    HardCaseSet set =
        inside_rays_set(octahedron(), "octahedron", HardCaseFamily::nonfinite, 64, options.seed);
    std::vector<Ray> aimed = set.rays;
    set.rays.clear(), set.must_hit.clear(), set.targets.clear();
    add_nonfinite_rays(set, aimed, true);
    battery.push_back(std::move(set));
  }
  if (mesh) append_mesh_nonfinite(battery, closed.empty());
  if (note) *note = notes;
  return battery;
}

}  // namespace raystep
