// The kinds of bounding volumes (accel/bounding_volumes.h, geometry/min_sphere.h, geometry/dop.h): every kind
// agrees with brute force, every volume test is conservative at every scale, the minimal sphere is minimal,
// the k-DOP is tight, and the counters count what they say.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bounding_volumes.h"
#include "raystep/accel/brute_force.h"
#include "raystep/geometry/dop.h"
#include "raystep/geometry/min_sphere.h"
#include "raystep/render/camera.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

constexpr BvolKind kKinds[] = {BvolKind::box, BvolKind::sphere, BvolKind::kdop, BvolKind::obb};

std::string kind_name(BvolKind k) {
  return bvol_kind_names()[size_t(k)];
}

// Many small objects: clusters of triangles (some long and thin, some flat), single spheres, and one object
// mixing both, all scaled by `scale` about a point `scale` * (3, -2, 5) away from the origin.
Geometry make_objects(uint32_t seed, float scale) {
  Geometry g;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  const glm::vec3 offset(3.f, -2.f, 5.f);
  auto at = [&](glm::vec3 p) { return scale * (p + offset); };
  for (int c = 0; c < 12; ++c) {
    g.begin_object("cluster", 0);
    glm::vec3 centre(4.f * u(rng), 4.f * u(rng), 4.f * u(rng));
    glm::vec3 stretch(1.f + 2.f * (c % 3 == 0), 1.f, c % 4 == 1 ? 0.f : 1.f);  // long, flat
    const int n = 1 + c * 3;
    for (int i = 0; i < n; ++i) {
      glm::vec3 p = centre + stretch * glm::vec3(u(rng), u(rng), u(rng));
      glm::vec3 q = p + 0.5f * stretch * glm::vec3(u(rng), u(rng), u(rng));
      glm::vec3 r = p + 0.5f * stretch * glm::vec3(u(rng), u(rng), u(rng));
      g.add_triangle(at(p), at(q), at(r));
    }
  }
  for (int s = 0; s < 4; ++s) {
    g.begin_object("sphere", 0);
    g.add_sphere(Sphere{at(glm::vec3(4.f * u(rng), 4.f * u(rng), 4.f * u(rng))), scale * (0.2f + 0.5f * s)});
  }
  g.begin_object("mixed", 0);
  glm::vec3 c(4.f * u(rng), 4.f * u(rng), 4.f * u(rng));
  g.add_triangle(at(c), at(c + glm::vec3(1.f, 0.f, 0.f)), at(c + glm::vec3(0.f, 1.f, 0.5f)));
  g.add_sphere(Sphere{at(c + glm::vec3(-1.f, 0.f, 0.f)), scale * 0.4f});
  return g;
}

// Random rays, rays aimed at vertices and edge points, rays along triangle edges (grazing, in the triangle's
// plane) and rays nearly tangent to the spheres.
std::vector<Ray> probe_rays(const Geometry& g, size_t count, uint32_t seed) {
  std::vector<Ray> rays = random_rays(g.bounds(), count, seed);
  std::vector<Ray> aimed = edge_rays(g, count, seed + 1);
  rays.insert(rays.end(), aimed.begin(), aimed.end());
  std::mt19937 rng(seed + 2);
  const Bounds3 ob = ray_origin_bounds(g.bounds());
  std::uniform_real_distribution<float> u(0.f, 1.f);
  auto origin = [&] { return ob.lo + glm::vec3(u(rng), u(rng), u(rng)) * (ob.hi - ob.lo); };
  for (uint32_t id = 0; id < g.size(); ++id) {
    if (g.type(id) == PrimType::triangle) {
      for (int k = 0; k < 3; ++k) {
        const glm::vec3 a = g.vertex(id, k), b = g.vertex(id, (k + 1) % 3);
        Ray along;  // in the triangle's plane, along an edge, from beyond its end
        along.origin = a - 2.f * (b - a);
        along.direction = b - a;
        rays.push_back(along);
        Ray at_vertex;  // exactly at a vertex from anywhere
        at_vertex.origin = origin();
        at_vertex.direction = a - at_vertex.origin;
        rays.push_back(at_vertex);
        // Along an axis through the vertex, the other components +0 or -0 (the slab tests' sign bits).
        Ray axis;
        const float zero = (id + k) % 2 ? 0.f : -0.f;
        axis.direction = glm::vec3(zero);
        axis.direction[k] = (id % 2) ? 1.f : -1.f;
        axis.origin = a - 3.f * (ob.hi[k] - ob.lo[k]) * axis.direction;
        rays.push_back(axis);
      }
      // In the triangle's plane when it lies in z = const (the flat clusters): direction z = +0 or -0.
      const glm::vec3 p0 = g.vertex(id, 0), p1 = g.vertex(id, 1), p2 = g.vertex(id, 2);
      if (p0.z == p1.z && p1.z == p2.z) {
        Ray in_plane;
        in_plane.origin = glm::vec3(ob.lo.x, ob.lo.y, p0.z);
        const glm::vec3 target = (p0 + p1 + p2) / 3.f;
        in_plane.direction =
            glm::vec3(target.x - in_plane.origin.x, target.y - in_plane.origin.y, id % 2 ? 0.f : -0.f);
        rays.push_back(in_plane);
      }
    } else {
      const Sphere& s = g.sphere(id);
      for (int k = 0; k < 4; ++k) {
        Ray tangent;
        tangent.origin = origin();
        glm::vec3 to_c = s.center - tangent.origin;
        glm::vec3 side = glm::normalize(glm::cross(to_c, glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, 1.f)));
        tangent.direction = s.center + s.radius * side - tangent.origin;
        rays.push_back(tangent);
      }
    }
  }
  return rays;
}

// The nearest hit of one object's primitives on the whole ray, by brute force.
bool object_hit(const Geometry& g, const Object& o, const Ray& ray, float* t) {
  WatertightRay wray(ray);
  float t_max = ray.tmax;
  bool found = false;
  for (uint32_t id = o.first_prim; id < o.first_prim + o.prim_count; ++id) {
    Hit h;
    if (g.intersect(id, ray, wray, t_max, &h)) {
      found = true;
      t_max = h.t;
    }
  }
  *t = t_max;
  return found;
}

// test::count_disagreements, naming the first disagreement in *first.
int disagreements(const Accelerator& acc, const BruteForce& brute, const std::vector<Ray>& rays,
                  std::string* first) {
  int bad = 0;
  for (const Ray& r : rays) {
    Hit a, b;
    bool ha = brute.intersect(r, &a), hb = acc.intersect(r, &b);
    bool oa = brute.occluded(r), ob = acc.occluded(r);
    if (ha == hb && a.prim == b.prim && a.t == b.t && oa == ob) continue;
    if (bad++ == 0)
      *first = "brute " + std::to_string(a.prim) + " t=" + std::to_string(a.t) + " occluded " +
               std::to_string(oa) + ", " + acc.name() + " " + std::to_string(b.prim) +
               " t=" + std::to_string(b.t) + " occluded " + std::to_string(ob);
  }
  return bad;
}

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(std::string(RAYSTEP_SOURCE_DIR) + "/scenes"))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(BoundingVolumes, KindNamesAreAcceleratorNames) {
  for (BvolKind k : kKinds) {
    EXPECT_EQ(make_accelerator(kind_name(k))->name(), kind_name(k));
    EXPECT_EQ(parse_bvol_kind(kind_name(k)), k);
  }
  EXPECT_EQ(BoundingVolumes().name(), "bvol");  // the default kind keeps today's name
  EXPECT_FALSE(parse_bvol_kind("bvol-cube"));
  EXPECT_THROW(make_accelerator("bvol-cube"), InputError);
}

TEST(BoundingVolumes, EveryKindAgreesWithBruteForceOnTheShippedScenes) {
  const std::vector<std::string> scenes = shipped_scenes();
  ASSERT_GE(scenes.size(), 5u);
  for (const std::string& path : scenes) {
    Scene scene = load_scene(path);
    BruteForce brute;
    brute.build(scene.geometry);
    std::vector<Ray> rays = camera_rays(scene.camera, 40, 30);
    std::vector<Ray> more = random_rays(scene.geometry.bounds(), 600, 5);
    rays.insert(rays.end(), more.begin(), more.end());
    if (scene.geometry.triangle_count() > 0) {
      more = edge_rays(scene.geometry, 600, 6);
      rays.insert(rays.end(), more.begin(), more.end());
    }
    for (BvolKind k : kKinds) {
      BoundingVolumes bvol(k);
      bvol.build(scene.geometry);
      std::string first;
      EXPECT_EQ(disagreements(bvol, brute, rays, &first), 0) << path << ": " << first;
    }
  }
}

TEST(BoundingVolumes, EveryKindAgreesWithBruteForceOnSoupsAndObjects) {
  Geometry soup = test::make_soup(21, 300, 12);  // one object of everything
  Geometry objects = make_objects(22, 1.f);
  for (const Geometry* g : {&soup, &objects}) {
    BruteForce brute;
    brute.build(*g);
    std::vector<Ray> rays = probe_rays(*g, 1500, 23);
    int hits = 0;
    for (const Ray& r : rays) {
      Hit h;
      hits += brute.intersect(r, &h);
    }
    EXPECT_GT(hits, int(rays.size() / 5));  // the rays do hit
    for (BvolKind k : kKinds) {
      BoundingVolumes bvol(k);
      bvol.build(*g);
      std::string first;
      EXPECT_EQ(disagreements(bvol, brute, rays, &first), 0) << g->size() << " primitives: " << first;
    }
  }
}

TEST(BoundingVolumes, RaysThatCannotHitMissEveryKind) {
  Geometry g = make_objects(5, 1.f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const glm::vec3 centre = g.bounds().center();
  std::vector<Ray> bad(7);
  for (Ray& r : bad) {
    r.origin = centre - glm::vec3(0.f, 0.f, 20.f);
    r.direction = glm::vec3(0.f, 0.f, 1.f);
  }
  bad[0].origin.x = nan;
  bad[1].direction.y = nan;
  bad[2].origin.z = -kInfinity;
  bad[3].direction = glm::vec3(0.f);
  bad[4].tmax = nan;
  bad[5].direction.z = kInfinity;
  bad[6].tmin = nan;
  for (BvolKind k : kKinds) {
    BoundingVolumes bvol(k);
    bvol.build(g);
    for (const Ray& r : bad) {
      Hit h;
      EXPECT_FALSE(bvol.intersect(r, &h)) << kind_name(k);
      EXPECT_FALSE(bvol.occluded(r)) << kind_name(k);
      for (uint32_t o = 0; o < g.objects().size(); ++o) EXPECT_FALSE(bvol.volume_hit(o, r)) << kind_name(k);
    }
  }
}

// Conservative: a ray that hits an object hits its volume, entering it no later than the hit, at scales 1e-6,
// 1 and 1e6 (coordinates far from the origin too: the objects sit scale * (3, -2, 5) away).
TEST(BoundingVolumes, EveryObjectHitIsAVolumeHitAtEveryScale) {
  for (float scale : {1e-6f, 1.f, 1e6f}) {
    Geometry g = make_objects(31, scale);
    const std::vector<Ray> rays = probe_rays(g, 2000, 32);
    for (BvolKind k : kKinds) {
      BoundingVolumes bvol(k);
      bvol.build(g);
      int object_hits = 0, missed = 0, late = 0;
      for (const Ray& r : rays) {
        for (uint32_t o = 0; o < g.objects().size(); ++o) {
          float t_hit;
          if (!object_hit(g, g.objects()[o], r, &t_hit)) continue;
          ++object_hits;
          float t_enter, t_exit;
          if (!bvol.volume_hit(o, r, &t_enter, &t_exit)) {
            ++missed;
          } else if (!(t_enter <= t_hit && t_hit <= t_exit)) {
            ++late;
          }
        }
      }
      EXPECT_GT(object_hits, 2000) << scale << " " << kind_name(k);
      EXPECT_EQ(missed, 0) << scale << " " << kind_name(k);
      EXPECT_EQ(late, 0) << scale << " " << kind_name(k);
    }
  }
}

// ---- The minimal sphere ----

// A brute-force reference: the smallest of the balls through every subset of 1 to 4 points that holds all the
// points. The ball through a subset is centred where the subset's affine hull meets the equidistant set: the
// Gram system sum_i l_i (u_i . u_j) = |u_j|^2 / 2 with u_i = p_i - p_0, solved by Gaussian elimination.
Ball reference_ball(const std::vector<glm::dvec3>& p) {
  Ball best;
  const int n = int(p.size());
  for (int mask = 1; mask < (1 << n); ++mask) {
    std::vector<int> idx;
    for (int i = 0; i < n; ++i)
      if (mask & (1 << i)) idx.push_back(i);
    if (idx.size() > 4) continue;
    const int k = int(idx.size()) - 1;
    std::vector<glm::dvec3> u(k);
    for (int i = 0; i < k; ++i) u[i] = p[idx[i + 1]] - p[idx[0]];
    double m[3][4] = {};
    for (int i = 0; i < k; ++i) {
      for (int j = 0; j < k; ++j) m[i][j] = glm::dot(u[i], u[j]);
      m[i][k] = 0.5 * glm::dot(u[i], u[i]);
    }
    bool singular = false;
    for (int c = 0; c < k && !singular; ++c) {
      int piv = c;
      for (int r = c + 1; r < k; ++r)
        if (std::abs(m[r][c]) > std::abs(m[piv][c])) piv = r;
      if (std::abs(m[piv][c]) < 1e-12 * (std::abs(m[0][0]) + std::abs(m[k - 1][k - 1]))) singular = true;
      for (int j = 0; j <= k; ++j) std::swap(m[c][j], m[piv][j]);
      for (int r = 0; r < k && !singular; ++r) {
        if (r == c) continue;
        const double f = m[r][c] / m[c][c];
        for (int j = 0; j <= k; ++j) m[r][j] -= f * m[c][j];
      }
    }
    if (singular) continue;
    glm::dvec3 centre = p[idx[0]];
    for (int i = 0; i < k; ++i) centre += (m[i][k] / m[i][i]) * u[i];
    double r = 0.0;
    for (const glm::dvec3& q : p) r = std::max(r, glm::distance(q, centre));
    if (best.radius < 0 || r < best.radius) {
      best.center = centre;
      best.radius = r;
    }
  }
  return best;
}

double farthest(const std::vector<glm::dvec3>& p, const glm::dvec3& c) {
  double r = 0.0;
  for (const glm::dvec3& q : p) r = std::max(r, glm::distance(q, c));
  return r;
}

TEST(MinimalSphere, MatchesTheBruteForceBallOnSmallRandomSets) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + trial % 8;
    std::vector<glm::dvec3> p(n);
    for (glm::dvec3& q : p) q = glm::dvec3(u(rng), u(rng), (trial % 5 == 0) ? 0.0 : u(rng));  // some planar
    const Ball ref = reference_ball(p);
    const Ball b = minimal_ball(p);
    EXPECT_NEAR(b.radius, ref.radius, 1e-9 * ref.radius) << trial;
    EXPECT_LE(farthest(p, b.center), b.radius * (1 + 1e-9)) << trial;
  }
}

TEST(MinimalSphere, SupportsOfTwoThreeAndFourPoints) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto with_inside = [&](std::vector<glm::dvec3> p, glm::dvec3 c, double r) {
    for (int i = 0; i < 40; ++i) {  // points well inside
      glm::dvec3 v(u(rng), u(rng), u(rng));
      if (glm::length(v) < 1.0) p.push_back(c + 0.5 * r * v);
    }
    return p;
  };
  const glm::dvec3 c(0.3, -0.7, 2.0);
  // Two points: the ball has them at the ends of a diameter.
  std::vector<glm::dvec3> two = with_inside({c + glm::dvec3(1.5, 0.2, 0.1), c - glm::dvec3(1.5, 0.2, 0.1)}, c,
                                            glm::length(glm::dvec3(1.5, 0.2, 0.1)));
  EXPECT_NEAR(minimal_ball(two).radius, glm::length(glm::dvec3(1.5, 0.2, 0.1)), 1e-12);
  // Three: an acute triangle's circumcircle (an equilateral one of circumradius 2).
  std::vector<glm::dvec3> three;
  for (int k = 0; k < 3; ++k)
    three.push_back(c + 2.0 * glm::dvec3(std::cos(2.1 * k), std::sin(2.1 * k), 0.0));
  Ball tri = reference_ball(three);
  three = with_inside(three, c, 1.0);
  EXPECT_NEAR(minimal_ball(three).radius, tri.radius, 1e-12);
  EXPECT_NEAR(tri.radius, 2.0, 1e-12);  // arcs of 2.1, 2.1 and 2.08 < pi: acute, so its circumcircle
  // Four: a regular tetrahedron's circumsphere, radius sqrt(3) for the corners (+-1, +-1, +-1) with an even
  // number of minus signs.
  std::vector<glm::dvec3> four = {c + glm::dvec3(1, 1, 1), c + glm::dvec3(1, -1, -1),
                                  c + glm::dvec3(-1, 1, -1), c + glm::dvec3(-1, -1, 1)};
  four = with_inside(four, c, std::sqrt(3.0));
  const Ball b4 = minimal_ball(four);
  EXPECT_NEAR(b4.radius, std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(glm::distance(b4.center, c), 0.0, 1e-12);
}

TEST(MinimalSphere, DegenerateSets) {
  const glm::dvec3 c(1e6, -1e6, 3.0);  // far from the origin
  // One point, and the same point many times.
  EXPECT_EQ(minimal_ball({c}).radius, 0.0);
  EXPECT_EQ(minimal_ball(std::vector<glm::dvec3>(50, c)).radius, 0.0);
  // Collinear points (with duplicates): half the segment.
  std::vector<glm::dvec3> line;
  for (int i = 0; i <= 40; ++i) line.push_back(c + double(i % 21) * glm::dvec3(0.1, 0.2, -0.2));
  EXPECT_NEAR(minimal_ball(line).radius, 0.5 * 20 * 0.3, 1e-9);
  // Cospherical: 500 points on a sphere (not in one hemisphere) give that sphere; and coplanar points on a
  // circle give the circle.
  std::mt19937 rng(43);
  std::normal_distribution<double> n;
  std::vector<glm::dvec3> sphere, circle;
  for (int i = 0; i < 500; ++i) {
    sphere.push_back(c + 2.5 * glm::normalize(glm::dvec3(n(rng), n(rng), n(rng))));
    glm::dvec3 v(n(rng), n(rng), 0.0);
    circle.push_back(c + 0.75 * glm::normalize(v));
    circle.push_back(circle.back());  // duplicates
  }
  const Ball bs = minimal_ball(sphere);
  EXPECT_NEAR(bs.radius, 2.5, 1e-9);
  EXPECT_LE(farthest(sphere, bs.center), bs.radius * (1 + 1e-11));
  EXPECT_NEAR(minimal_ball(circle).radius, 0.75, 1e-9);
  // Every point lies in the float sphere exactly (in double arithmetic on the float data).
  for (const std::vector<glm::dvec3>* set : {&line, &sphere, &circle}) {
    std::vector<glm::vec3> pts;
    for (const glm::dvec3& p : *set) pts.emplace_back(p);
    const Sphere s = bounding_sphere(pts, {});
    for (const glm::vec3& p : pts)
      EXPECT_LE(glm::distance(glm::dvec3(p), glm::dvec3(s.center)), double(s.radius));
  }
  // A sphere primitive's bounding sphere is the sphere itself (to a float ulp).
  const Sphere prim{glm::vec3(1e3f, 2.f, -5.f), 0.125f};
  const Sphere s = bounding_sphere({}, {prim});
  EXPECT_EQ(s.center, prim.center);
  EXPECT_GE(s.radius, prim.radius);
  EXPECT_LE(s.radius, next_float_up(prim.radius));
}

TEST(MinimalSphere, BoundingSpheresOfObjectsHoldEveryPointAndAreNoLargerThanTheReference) {
  Geometry g = make_objects(51, 1.f);
  BoundingVolumes bvol(BvolKind::sphere);
  bvol.build(g);
  for (uint32_t o = 0; o < g.objects().size(); ++o) {
    const Object& obj = g.objects()[o];
    const Sphere& s = bvol.spheres()[o];
    std::vector<glm::dvec3> pts;
    for (uint32_t id = obj.first_prim; id < obj.first_prim + obj.prim_count; ++id) {
      if (g.type(id) == PrimType::sphere) {
        const Sphere& p = g.sphere(id);
        EXPECT_LE(glm::distance(glm::dvec3(p.center), glm::dvec3(s.center)) + p.radius, double(s.radius));
        continue;
      }
      for (int k = 0; k < 3; ++k) pts.emplace_back(g.vertex(id, k));
    }
    for (const glm::dvec3& p : pts) EXPECT_LE(glm::distance(p, glm::dvec3(s.center)), double(s.radius));
    if (obj.name == "cluster" && pts.size() <= 12) {  // small enough for the brute-force reference
      EXPECT_NEAR(double(s.radius), reference_ball(pts).radius, 1e-6 * double(s.radius)) << o;
    }
  }
}

// ---- The k-DOP and the oriented box ----

TEST(Kdop, HoldsEveryPointAndEachSlabTouchesOne) {
  for (float scale : {1e-6f, 1.f, 1e6f}) {
    Geometry g = make_objects(61, scale);
    BoundingVolumes kdop(BvolKind::kdop), obb(BvolKind::obb);
    kdop.build(g);
    obb.build(g);
    for (uint32_t o = 0; o < g.objects().size(); ++o) {
      const Object& obj = g.objects()[o];
      if (obj.name != "cluster") continue;
      std::vector<glm::dvec3> pts;
      for (uint32_t id = obj.first_prim; id < obj.first_prim + obj.prim_count; ++id)
        for (int k = 0; k < 3; ++k) pts.emplace_back(g.vertex(id, k));
      const double size = glm::length(glm::dvec3(obj.bounds.hi) - glm::dvec3(obj.bounds.lo)) +
                          glm::length(glm::dvec3(obj.bounds.hi));
      for (int k = 0; k < 7; ++k) {
        const glm::dvec3 n = kdop_directions()[k];
        double lo = kInfinity, hi = -kInfinity;
        for (const glm::dvec3& p : pts) {
          lo = std::min(lo, glm::dot(n, p));
          hi = std::max(hi, glm::dot(n, p));
        }
        const double s_lo = kdop.kdops()[o][2 * k], s_hi = kdop.kdops()[o][2 * k + 1];
        EXPECT_LE(s_lo, lo);
        EXPECT_GE(s_hi, hi);
        EXPECT_LE(lo - s_lo, 1e-13 * size) << "slab " << k << " does not touch a point";
        EXPECT_LE(s_hi - hi, 1e-13 * size) << "slab " << k << " does not touch a point";
      }
      // The oriented box holds every point and is no larger than the axis-aligned box.
      const OrientedBox& b = obb.oriented_boxes()[o];
      for (const glm::dvec3& p : pts)
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE(b.lo[k], glm::dot(b.axes[k], p));
          EXPECT_GE(b.hi[k], glm::dot(b.axes[k], p));
        }
      const double ex = b.hi[0] - b.lo[0], ey = b.hi[1] - b.lo[1], ez = b.hi[2] - b.lo[2];
      EXPECT_LE(2 * (ex * ey + ey * ez + ez * ex), double(obj.bounds.surface_area()) * (1 + 1e-6));
    }
  }
}

// ---- Counting ----

// One long thin triangle along the diagonal of the xy-plane, and a ray through the part of its box that the
// triangle leaves empty: the box and the sphere let it in (a false positive), the k-DOP's diagonal slab and
// the oriented box (along the triangle) keep it out.
TEST(BoundingVolumes, CountsVolumeTestsAndFalsePositives) {
  Geometry g;
  g.begin_object("triangle", 0);
  g.add_triangle(glm::vec3(0, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0.9f, 1.1f, 0));
  Ray r;
  r.origin = glm::vec3(0.8f, 0.2f, -1.f);
  Ray through = r;
  through.origin = glm::vec3(0.633f, 0.7f, -1.f);
  const int expected_false_positives[] = {1, 1, 0, 0};
  for (BvolKind k : kKinds) {
    BoundingVolumes bvol(k);
    bvol.build(g);
    CountingRecorder c;
    Hit h;
    EXPECT_FALSE(bvol.intersect_counted(r, &h, c));
    EXPECT_EQ(c.volume_tests, 1u);
    EXPECT_EQ(c.volume_false_positives, uint64_t(expected_false_positives[int(k)])) << kind_name(k);
    EXPECT_EQ(c.volume_hits, c.volume_false_positives);
    EXPECT_TRUE(bvol.intersect_counted(through, &h, c));
    EXPECT_EQ(c.volume_tests, 2u);
    EXPECT_EQ(c.volume_false_positives, uint64_t(expected_false_positives[int(k)])) << kind_name(k);
    EXPECT_EQ(c.prim_tests, 1u + expected_false_positives[int(k)]);
  }
}

// On many objects: one volume test per object per ray, a false positive for every entered object without a
// hit at most, and the k-DOP, whose first three slabs are the box, never lets more rays in than the box.
TEST(BoundingVolumes, CountersAddUpOnManyObjects) {
  Geometry g = make_objects(71, 1.f);
  const std::vector<Ray> rays = probe_rays(g, 1000, 72);
  uint64_t hits_of[4] = {};
  for (BvolKind k : kKinds) {
    BoundingVolumes bvol(k);
    bvol.build(g);
    CountingRecorder c;
    for (const Ray& r : rays) {
      Hit h;
      bvol.intersect_counted(r, &h, c);
    }
    EXPECT_EQ(c.volume_tests, rays.size() * g.objects().size());
    EXPECT_LE(c.volume_false_positives, c.nodes);  // nodes: the volumes entered
    EXPECT_LE(c.nodes, c.volume_hits);
    EXPECT_GT(c.volume_false_positives, 0u);
    hits_of[int(k)] = c.volume_hits;
  }
  EXPECT_LE(hits_of[int(BvolKind::kdop)], hits_of[int(BvolKind::box)]);
}

}  // namespace
}  // namespace raystep
