// Scale and translation invariance: every shipped scene and mesh, scaled by 1e-6 and 1e6 and
// translated by 1e5 with its camera and lights, renders the same picture with every structure, and rays
// spawned from its surfaces never meet their own surface again. Geometry is float, so "the same picture" is
// defined in two parts: on the transformed scene every structure agrees exactly with brute force (the same
// primitive and t for every ray the tracer casts, the same colour at every pixel); against the untransformed
// scene, a pixel may show another primitive only where one of its rays passes within the rounding distance of
// an edge or a sphere's silhouette (the distance the transformation's rounding can move a ray relative to the
// geometry), and another colour only there or within the bound its faces' rounded normals give; such pixels
// are counted and bounded. Also the far-origin tiny-triangle case: a triangle a thousandth wide 1e5 and 1e6
// away from the origin, which no structure's box, plane or cell arithmetic may cull; the regression cases of
// the faults these tests found; and the kd builder's clip as the library compiled it (GCC 12.2's SLP bug).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "exact_reference.h"
#include "raystep/accel/accelerator.h"
#include "raystep/accel/brute_force.h"
#include "raystep/geometry/spawn.h"
#include "raystep/geometry/triangle_clip.h"
#include "raystep/io/scene_loader.h"
#include "raystep/render/camera.h"
#include "raystep/render/whitted.h"
#include "test_budget.h"
#include "test_scenes.h"

namespace raystep::kd {
// The kd-tree builder's clip (core/src/accel/kdtree_build_common.h, private): the copy of triangle_clip.h
// that the library was compiled with, not the one this test's translation unit compiles.
Bounds3 clipped_bounds(const Geometry& geometry, uint32_t prim, const Bounds3& box);
}  // namespace raystep::kd

namespace raystep {
namespace {

// (A quarter of the pixels in the sanitizer passes, test_budget.h.)
constexpr int kWidth = test::kSanitized ? 24 : 48, kHeight = test::kSanitized ? 18 : 36;
const char* const kStructures[] = {"grid", "kd", "bvh", "bvh4", "bvh8", "octree", "bsp"};

// p -> scale * p + offset, computed in double and rounded once to float (as a modelling tool would write the
// transformed file).
struct Transform {
  const char* name;
  double scale;
  glm::dvec3 offset;
  glm::vec3 apply(const glm::vec3& p) const { return glm::vec3(glm::dvec3(p) * scale + offset); }
  // A transformed point back in the untransformed scene's units (double, no rounding beyond the inputs').
  glm::dvec3 back(const glm::vec3& p) const { return (glm::dvec3(p) - offset) / scale; }
};
const Transform kTransforms[] = {{"scale 1e-6", 1e-6, glm::dvec3(0.0)},
                                 {"scale 1e6", 1e6, glm::dvec3(0.0)},
                                 {"translate 1e5", 1.0, glm::dvec3(1e5, 1e5, 1e5)}};

// The scene moved by x: geometry, camera (eye, look_at, the orthographic view's height) and point lights.
// Directions (the up vector, directional lights, vertex normals) and colours are unchanged.
Scene transform_scene(const Scene& in, const Transform& x) {
  Scene out;
  out.path = in.path;
  out.lights = in.lights;
  out.materials = in.materials;
  out.render = in.render;
  out.camera = in.camera;
  out.camera.eye = x.apply(in.camera.eye);
  out.camera.look_at = x.apply(in.camera.look_at);
  out.camera.ortho_height = float(double(in.camera.ortho_height) * x.scale);
  for (Light& l : out.lights)
    if (l.type == LightType::point) l.position = x.apply(l.position);
  const Geometry& g = in.geometry;
  for (const Object& obj : g.objects()) {
    out.geometry.begin_object(obj.name, obj.material);
    for (uint32_t id = obj.first_prim; id < obj.first_prim + obj.prim_count; ++id) {
      if (g.type(id) == PrimType::triangle) {
        uint32_t t = out.geometry.add_triangle(x.apply(g.vertex(id, 0)), x.apply(g.vertex(id, 1)),
                                               x.apply(g.vertex(id, 2)));
        if (g.has_vertex_normals(id))
          out.geometry.set_vertex_normals(t, g.vertex_normal(id, 0), g.vertex_normal(id, 1),
                                          g.vertex_normal(id, 2));
      } else {
        const Sphere& s = g.sphere(id);
        out.geometry.add_sphere(Sphere{x.apply(s.center), float(double(s.radius) * x.scale)});
      }
    }
  }
  return out;
}

// Every shipped scene, and every shipped mesh as a bare mesh (its framing camera and a light at the eye).
std::vector<std::string> shipped_scenes() {
  std::vector<std::string> paths;
  for (const char* folder : {"/scenes", "/scenes/meshes"})
    for (const auto& e : std::filesystem::directory_iterator(std::string(RAYSTEP_SOURCE_DIR) + folder)) {
      std::string ext = e.path().extension().string();
      if (ext == ".json" || ext == ".obj") paths.push_back(e.path().string());
    }
  std::sort(paths.begin(), paths.end());
  return paths;
}

// Brute force's answers to a set of rays (nearest hit and occlusion), computed once for all structures.
struct Answers {
  std::vector<Hit> hits;
  std::vector<uint8_t> occluded;
};
Answers answers(const Accelerator& accel, const std::vector<Ray>& rays) {
  Answers a;
  a.hits.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    accel.intersect(rays[i], &a.hits[i]);
    a.occluded.push_back(accel.occluded(rays[i]));
  }
  return a;
}
// The rays on which the structure's answer differs from brute force's (test_scenes.h's rule: another
// primitive, another t or another occlusion).
int disagreements(const Accelerator& accel, const Answers& brute, const std::vector<Ray>& rays) {
  int bad = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    Hit h;
    bool found = accel.intersect(rays[i], &h);
    const Hit& b = brute.hits[i];
    bad += found != b.found() || h.prim != b.prim || h.t != b.t ||
           accel.occluded(rays[i]) != bool(brute.occluded[i]);
  }
  return bad;
}

// A ray the tracer cast, and what brute force says it meets.
struct TracedRay {
  Ray ray;
  RayKind kind;
  int depth;
  int parent;  // index of the ray whose hit spawned it (-1: primary)
  Hit hit;
};

// One picture: per pixel the primary ray's primitive and the colour, and every ray of the pixel's tree.
struct Picture {
  std::vector<int32_t> prim;
  std::vector<glm::vec3> colour;
  std::vector<TracedRay> rays;
  std::vector<uint32_t> first_ray;  // pixel p's rays are rays[first_ray[p], first_ray[p + 1])
};

Picture render(const Scene& scene, const Accelerator& accel, bool keep_rays) {
  ProjectiveCamera camera(scene.camera, kWidth, kHeight);
  WhittedTracer tracer(scene, accel);
  Picture pic;
  std::vector<int> last_at_depth(64, -1);
  RayListener listener = [&](const Ray& r, RayKind kind, int depth) {
    TracedRay t{r, kind, depth, depth > 0 ? last_at_depth[size_t(depth - 1)] : -1, Hit{}};
    last_at_depth[size_t(depth)] = int(pic.rays.size());
    pic.rays.push_back(t);
  };
  if (keep_rays) tracer.set_listener(&listener);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      pic.first_ray.push_back(uint32_t(pic.rays.size()));
      Ray r = camera.generate(float(x) + 0.5f, float(y) + 0.5f);
      Hit h;
      accel.intersect(r, &h);
      pic.prim.push_back(h.prim);
      RayCounts counts;
      pic.colour.push_back(tracer.trace_primary(r, &counts));
    }
  pic.first_ray.push_back(uint32_t(pic.rays.size()));
  for (TracedRay& t : pic.rays) accel.intersect(t.ray, &t.hit);
  return pic;
}

// ---- The rounding distance ----

// Closest approach of the segment o + s d, s in [s0, s1], to the segment [a, b]: the distance and its s.
void segment_distance(const glm::dvec3& o, const glm::dvec3& d, double s0, double s1, const glm::dvec3& a,
                      const glm::dvec3& b, double* dist, double* s_at) {
  // Minimise |o + s d - a - u e| over s in [s0, s1], u in [0, 1]: the unconstrained solution clamped, then
  // each parameter re-solved for the other's clamped value (exact for two segments).
  glm::dvec3 e = b - a, w = o - a;
  double dd = glm::dot(d, d), ee = glm::dot(e, e), de = glm::dot(d, e), dw = glm::dot(d, w),
         ew = glm::dot(e, w);
  double den = dd * ee - de * de;
  double s = den > 1e-300 ? (de * ew - ee * dw) / den : s0;
  s = std::clamp(s, s0, s1);
  double u = ee > 0 ? std::clamp((de * s + ew) / ee, 0.0, 1.0) : 0.0;
  s = std::clamp((de * u - dw) / dd, s0, s1);
  u = ee > 0 ? std::clamp((de * s + ew) / ee, 0.0, 1.0) : 0.0;
  *dist = glm::length(o + s * d - a - u * e);
  *s_at = s;
}

// How far the transformation's rounding may move the geometry and the rays, in the untransformed scene's
// units.
struct Rounding {
  double position;           // a vertex, sphere centre, eye or light: half an ulp per axis of its
                             // transformed coordinate, sqrt(3) of that as a distance, back in scene units
  double camera_angle;       // the primary rays' direction: eye and look_at each off by `position`
  std::vector<double> turn;  // per primitive: how far its normal turns (radians), so a secondary ray too
};

double ulp_distance(const Transform& x, const glm::vec3& p) {
  glm::vec3 q = x.apply(p);
  double u = 0;
  for (int a = 0; a < 3; ++a) u = std::max(u, double(next_float_up(std::fabs(q[a])) - std::fabs(q[a])));
  return 0.5 * std::sqrt(3.0) * u / x.scale;
}

Rounding rounding_of(const Scene& scene, const Scene& moved, const Transform& x) {
  Rounding r;
  const Geometry& g = scene.geometry;
  Bounds3 all = g.bounds();
  all.extend(scene.camera.eye);
  all.extend(scene.camera.look_at);
  r.position = std::max(ulp_distance(x, all.lo), ulp_distance(x, all.hi));
  double view = glm::length(glm::dvec3(scene.camera.look_at) - glm::dvec3(scene.camera.eye));
  r.camera_angle = 2 * r.position / view;
  for (uint32_t id = 0; id < g.size(); ++id) {
    if (g.type(id) == PrimType::sphere) {
      r.turn.push_back(2 * r.position / double(g.sphere(id).radius));
      continue;
    }
    glm::dvec3 p[3], q[3];
    for (int k = 0; k < 3; ++k)
      p[k] = glm::dvec3(g.vertex(id, k)), q[k] = x.back(moved.geometry.vertex(id, k));
    glm::dvec3 n0 = glm::cross(p[1] - p[0], p[2] - p[0]), n1 = glm::cross(q[1] - q[0], q[2] - q[0]);
    double l0 = glm::length(n0), l1 = glm::length(n1);
    double angle = l0 > 0 && l1 > 0 ? std::acos(std::clamp(glm::dot(n0, n1) / (l0 * l1), -1.0, 1.0)) : M_PI;
    r.turn.push_back(angle);
  }
  return r;
}

// Does ray k of the tree pass within its rounding distance of an edge or silhouette it could meet? Its
// rounding distance at parameter s: where it starts (the parent's, at the parent's hit) plus its direction's
// error times the distance travelled.
bool near_edge(const Scene& scene, const Picture& pic, size_t k, const Rounding& rnd,
               std::vector<double>* start) {
  const TracedRay& tr = pic.rays[k];
  const Geometry& g = scene.geometry;
  const glm::dvec3 o(tr.ray.origin), d(tr.ray.direction);
  const double len = glm::length(d);
  double delta0, angle;
  int own = -1;
  if (tr.parent < 0) {
    delta0 = rnd.position;
    angle = rnd.camera_angle;
  } else {
    const TracedRay& p = pic.rays[size_t(tr.parent)];
    own = p.hit.prim;
    delta0 = (*start)[size_t(tr.parent)];
    // A reflected or refracted ray turns by up to twice its surface's normal (and its parent's own turn
    // reaches it through the hit point, in delta0); a shadow ray keeps its direction up to its origin's move.
    angle = tr.kind == RayKind::shadow ? 0.0 : 2 * rnd.turn[size_t(own)] + rnd.camera_angle;
  }
  // The segment: to the hit, or to the end of the scene (for a miss).
  Bounds3 b = g.bounds();
  double reach = glm::length(glm::dvec3(b.hi) - glm::dvec3(b.lo)) + glm::length(glm::dvec3(b.center()) - o);
  double s0 = double(tr.ray.tmin),
         s1 = tr.hit.found() ? double(tr.hit.t) : std::min(double(tr.ray.tmax), reach / len);
  // Where this ray hits, the next ray starts: the hit point's own rounding distance.
  (*start)[k] = 2 * (delta0 + angle * s1 * len);
  bool near = false;
  for (uint32_t id = 0; id < g.size() && !near; ++id) {
    if (int32_t(id) == own) continue;
    if (g.type(id) == PrimType::sphere) {
      const Sphere& sp = g.sphere(id);
      glm::dvec3 c(sp.center);
      double s = std::clamp(glm::dot(c - o, d) / (len * len), s0, s1);
      double dist = std::fabs(glm::length(o + s * d - c) - double(sp.radius));
      near = dist <= 2 * (delta0 + angle * s * len);
      continue;
    }
    for (int e = 0; e < 3 && !near; ++e) {
      double dist, s;
      segment_distance(o, d, s0, s1, glm::dvec3(g.vertex(id, e)), glm::dvec3(g.vertex(id, (e + 1) % 3)),
                       &dist, &s);
      near = dist <= 2 * (delta0 + angle * s * len);
    }
  }
  return near;
}

// How far a pixel's colour may move while none of its rays changes what it meets. Shading is Lipschitz in the
// angles it is computed from (n . l, and the Phong lobe (r . v)^shininess, whose slope is at most shininess),
// and the rounding turns the hit primitives' normals (turn), the rays (a primary ray by camera_angle, a
// mirror or refracted ray by up to twice its surface's turn) and the directions to the point lights (both
// ends moved by `position`). Far from the origin a flat face's triangles turn by up to 1e-3 (a vertex moved
// by 1/256 on a triangle 0.1 wide), so its shade moves by about that much: a change no ray's path explains,
// and a bounded one.
double colour_bound(const Scene& scene, const Picture& pic, size_t pixel, const Rounding& rnd,
                    std::vector<double>* ray_angle) {
  double power = 0;
  for (const Light& l : scene.lights)
    power += double(l.intensity) * double(glm::max(l.color.x, glm::max(l.color.y, l.color.z)));
  double bound = 1e-3;
  for (uint32_t k = pic.first_ray[pixel]; k < pic.first_ray[pixel + 1]; ++k) {
    const TracedRay& tr = pic.rays[k];
    double angle = rnd.camera_angle;
    if (tr.parent >= 0) {
      const TracedRay& parent = pic.rays[size_t(tr.parent)];
      angle = tr.kind == RayKind::shadow
                  ? 0.0
                  : (*ray_angle)[size_t(tr.parent)] + 2 * rnd.turn[size_t(parent.hit.prim)];
    }
    (*ray_angle)[k] = angle;
    if (!tr.hit.found() || tr.kind == RayKind::shadow) continue;
    const Material& m = scene.materials[scene.geometry.material(uint32_t(tr.hit.prim))];
    double lobe = double(glm::max(m.diffuse.x, glm::max(m.diffuse.y, m.diffuse.z))) +
                  double(glm::max(m.specular.x, glm::max(m.specular.y, m.specular.z))) * double(m.shininess);
    glm::dvec3 q = glm::dvec3(tr.ray.origin) + double(tr.hit.t) * glm::dvec3(tr.ray.direction);
    double light_angle = 0;
    for (const Light& l : scene.lights)
      if (l.type == LightType::point)
        light_angle = std::max(light_angle, 2 * rnd.position / glm::length(glm::dvec3(l.position) - q));
    bound += 2 * power * lobe * (rnd.turn[size_t(tr.hit.prim)] + angle + light_angle);
  }
  return bound;
}

// ---- Part 1: every shipped scene, transformed ----

struct Figures {
  int pixels = 0, rays = 0, structure_disagreements = 0, prim_changed = 0, colour_changed = 0, near_edge = 0,
      unexplained = 0;
};

// One test per transform (each a third of the work, so that no test takes a minute under the sanitizers).
class ScaleInvarianceAt : public ::testing::TestWithParam<int> {};  // the picture: kTransforms[i]
class SpawnedRaysAt : public ::testing::TestWithParam<int> {};      // spawned rays: 3 is the scene as shipped
std::string transform_test_name(const ::testing::TestParamInfo<int>& info) {
  static const char* const names[] = {"Scale1eMinus6", "Scale1e6", "Translate1e5", "Identity"};
  return names[info.param];
}

TEST_P(ScaleInvarianceAt, EveryShippedSceneRendersTheSamePicture) {
  const int xi = GetParam();
  Figures totals[3];
  for (const std::string& path : shipped_scenes()) {
    Scene scene = load_scene(path);
    BruteForce brute;
    brute.build(scene.geometry);
    Picture original = render(scene, brute, true);
    {
      const Transform& x = kTransforms[xi];
      Scene moved = transform_scene(scene, x);
      BruteForce moved_brute;
      moved_brute.build(moved.geometry);
      Picture reference = render(moved, moved_brute, true);
      std::vector<Ray> all_rays;
      for (const TracedRay& t : reference.rays) all_rays.push_back(t.ray);
      Figures& f = totals[xi];
      f.pixels += kWidth * kHeight;
      f.rays += int(all_rays.size());
      // Every structure agrees with brute force on the transformed scene, on every ray the tracer casts for
      // the picture (primary, shadow, reflected, refracted): then it renders the same picture, colour for
      // colour, since the tracer's rays and colours follow from these answers alone.
      Answers truth = answers(moved_brute, all_rays);
      for (const char* name : kStructures) {
        std::unique_ptr<Accelerator> accel = make_accelerator(name);
        accel->build(moved.geometry);
        int bad = disagreements(*accel, truth, all_rays);
        EXPECT_EQ(bad, 0) << path << ", " << x.name << ", " << name;
        f.structure_disagreements += bad;
      }
      // Against the untransformed picture: a pixel differs only where a ray passes near an edge.
      Rounding rnd = rounding_of(scene, moved, x);
      std::vector<double> start(original.rays.size(), 0.0), ray_angle(original.rays.size(), 0.0);
      int unexplained = 0;
      for (size_t p = 0; p < original.prim.size(); ++p) {
        bool prim_changed = original.prim[p] != reference.prim[p];
        double dc = glm::length(glm::dvec3(original.colour[p]) - glm::dvec3(reference.colour[p]));
        double bound = colour_bound(scene, original, p, rnd, &ray_angle);
        bool colour_changed = dc > 1e-3;
        f.prim_changed += prim_changed;
        f.colour_changed += colour_changed && !prim_changed;
        if (!prim_changed && dc <= bound) continue;  // the same primitive, the colour within its bound
        bool near = false;
        for (uint32_t k = original.first_ray[p]; k < original.first_ray[p + 1]; ++k)
          near |= near_edge(scene, original, k, rnd, &start);
        f.near_edge += near;
        if (!near) {
          ++unexplained;
          ADD_FAILURE() << path << ", " << x.name << ": pixel " << p << " changed (primitive "
                        << original.prim[p] << " -> " << reference.prim[p] << ", colour by " << dc
                        << ", bound " << bound << ") with no ray near an edge";
        }
      }
      f.unexplained += unexplained;
    }
  }
  // The bound on the pixels that change. A pixel changes only where one of its rays passes within the
  // rounding distance of an edge or a silhouette (asserted above), so the changed pixels are about the
  // image's edge length in pixels times twice that distance in pixels. Scaled by 1e-6 or 1e6 the distance is
  // a few ulps of the scene's size (3e-7 of it): only the rays aimed exactly at edges and vertices change
  // (robustness.json and leak.json aim them on purpose), well under 0.5% of the pixels. Moved to 1e5 it is
  // 0.007 to 0.03 units (half an ulp of 1e5 in each of the vertices, the eye and the look-at point), a tenth
  // to a third of a pixel's footprint in these 48 x 36 pictures: of the 18 scenes' edges, some 2% of the
  // pixels.
  {
    const Figures& t = totals[xi];
    std::printf(
        "%-13s %d pixels, %d rays: %d disagreements, %d pixels with another primitive, %d with another "
        "colour only (%d of the changed ones explained by an edge), %d unexplained\n",
        kTransforms[xi].name, t.pixels, t.rays, t.structure_disagreements, t.prim_changed, t.colour_changed,
        t.near_edge, t.unexplained);
    EXPECT_LE(t.prim_changed, (xi < 2 ? 0.005 : 0.02) * t.pixels) << kTransforms[xi].name;
    EXPECT_GT(t.rays, t.pixels) << kTransforms[xi].name;
  }
}

// ---- Part 1b: spawned rays never meet their own surface ----

// A ray spawned from a surface point, and what a re-hit of its own surface would be.
struct Spawned {
  Ray ray;
  uint32_t own;    // the primitive it leaves
  double cos_out;  // cosine of its direction with the surface's outward normal at the spawn point (spheres)
};

// Is `hit` the spawned ray meeting its own surface again? A triangle is flat: any hit on it is. A sphere is
// met again legitimately by a ray that leaves inwards, at the far end of its chord, 2 r |cos| from the spawn
// point; a hit within half of that (or any hit, for a ray that leaves outwards) is its own surface again.
bool is_self_hit(const Geometry& g, const Spawned& s, const Hit& hit) {
  if (hit.prim != int32_t(s.own)) return false;
  if (g.type(s.own) == PrimType::triangle) return true;
  if (s.cos_out >= 0) return true;
  double travelled = double(hit.t) * glm::length(glm::dvec3(s.ray.direction));
  return travelled < -s.cos_out * double(g.sphere(s.own).radius);
}

// The rays a hit spawns: as the tracer spawns them (towards every light, mirror, refracted into the surface
// with ior 1.5), and grazing ones: 1e-3 off the tangent plane on both sides of a triangle (outwards only from
// a sphere), and 1e-6 off it outwards. (An inward ray that grazes a sphere meets it again after a chord of 2
// r 1e-3, shorter than the spawn point's error region at 1e5, so nothing in float can tell that exit from the
// spawn point; the tracer never casts one: a refracted ray leaves at least 48 degrees off the tangent plane.)
std::vector<Spawned> spawned_rays(const Scene& scene, const Ray& ray, const Hit& hit) {
  const Geometry& g = scene.geometry;
  uint32_t id = uint32_t(hit.prim);
  glm::vec3 p, err, n;
  glm::dvec3 outward;
  if (g.type(id) == PrimType::triangle) {
    const glm::vec3 &p0 = g.vertex(id, 0), &p1 = g.vertex(id, 1), &p2 = g.vertex(id, 2);
    TriangleHit th{hit.t, 1.f - hit.b1 - hit.b2, hit.b1, hit.b2};
    p = triangle_point(th, p0, p1, p2, &err);
    n = triangle_normal(p0, p1, p2);
  } else {
    p = sphere_point(ray, g.sphere(id), hit.t, &err);
    n = p - g.sphere(id).center;
  }
  n = glm::normalize(n);
  outward = glm::dvec3(n);
  const glm::vec3 d = glm::normalize(ray.direction);
  if (glm::dot(n, d) > 0) n = -n;  // towards the incoming ray, as the tracer turns it
  std::vector<Spawned> out;
  auto add = [&](const Ray& r) {
    out.push_back({r, id, glm::dot(glm::normalize(glm::dvec3(r.direction)), outward)});
  };
  for (const Light& l : scene.lights)
    add(l.type == LightType::point ? spawn_ray_to(p, err, n, l.position)
                                   : spawn_ray(p, err, n, -glm::normalize(l.direction)));
  add(spawn_ray(p, err, n, reflect(d, n)));
  glm::vec3 t;
  if (refract(d, n, 1.f / 1.5f, &t)) add(spawn_ray(p, err, n, t));
  glm::vec3 tangent = glm::normalize(d - glm::dot(d, n) * n);
  if (is_finite(tangent))
    for (float off : {1e-3f, -1e-3f, 1e-6f}) {
      glm::vec3 w = tangent + off * n;
      if (g.type(id) == PrimType::sphere && glm::dot(glm::dvec3(w), outward) < 0) continue;
      add(spawn_ray(p, err, n, w));
    }
  return out;
}

TEST_P(SpawnedRaysAt, NeverMeetTheirOwnSurface) {
  const Transform identity{"identity", 1.0, glm::dvec3(0.0)};
  const int xi = GetParam();
  int points[4] = {}, spawned[4] = {}, self_hits[4] = {}, bad[4] = {};
  for (const std::string& path : shipped_scenes()) {
    Scene original = load_scene(path);
    {
      const Transform& x = xi < 3 ? kTransforms[xi] : identity;
      Scene scene = transform_scene(original, x);
      BruteForce brute;
      brute.build(scene.geometry);
      // Surface points: where the primary rays of every other pixel (a checkerboard) meet the scene.
      ProjectiveCamera camera(scene.camera, kWidth, kHeight);
      std::vector<Spawned> from;
      for (int y = 0; y < kHeight; ++y)
        for (int px = y % 2; px < kWidth; px += 2) {
          Ray r = camera.generate(float(px) + 0.5f, float(y) + 0.5f);
          Hit h;
          if (!brute.intersect(r, &h)) continue;
          ++points[xi];
          for (const Spawned& s : spawned_rays(scene, r, h)) from.push_back(s);
        }
      std::vector<Ray> rays;
      for (const Spawned& s : from) rays.push_back(s.ray);
      spawned[xi] += int(rays.size());
      // The surface alone, whatever else lies in the way, then each structure's nearest hit.
      int own_hits = 0;
      for (const Spawned& s : from) {
        Hit alone;
        if (scene.geometry.intersect(s.own, s.ray, WatertightRay(s.ray), s.ray.tmax, &alone))
          own_hits += is_self_hit(scene.geometry, s, alone);
      }
      EXPECT_EQ(own_hits, 0) << path << ", " << x.name;
      self_hits[xi] += own_hits;
      Answers truth = answers(brute, rays);
      for (const char* name : kStructures) {
        std::unique_ptr<Accelerator> accel = make_accelerator(name);
        accel->build(scene.geometry);
        int self = 0;
        for (const Spawned& s : from) {
          Hit h;
          accel->intersect(s.ray, &h);
          self += is_self_hit(scene.geometry, s, h);
        }
        int differ = disagreements(*accel, truth, rays);
        EXPECT_EQ(self, 0) << path << ", " << x.name << ", " << name;
        EXPECT_EQ(differ, 0) << path << ", " << x.name << ", " << name;
        self_hits[xi] += self;
        bad[xi] += differ;
      }
    }
  }
  std::printf("%-13s %5d surface points, %6d spawned rays, %d self-hits, %d disagreements (7 structures)\n",
              xi < 3 ? kTransforms[xi].name : "identity", points[xi], spawned[xi], self_hits[xi], bad[xi]);
}

// Scaled by 1e-6 and 1e6, moved to 1e5; the spawned rays also as shipped.
INSTANTIATE_TEST_SUITE_P(ScaleInvariance, ScaleInvarianceAt, ::testing::Range(0, 3), transform_test_name);
INSTANTIATE_TEST_SUITE_P(ScaleInvariance, SpawnedRaysAt, ::testing::Range(0, 4), transform_test_name);

// ---- Regression cases of the fixes these tests found ----

// The unit box of 12 x 12 quads per face (scenes/meshes/subdivided_box.obj) moved to 1e5, where its grid's
// cells (1/36 wide) are 3.6 ulps of their coordinates: the 3D-DDA stepped tMax by tDelta, drifted 0.006 from
// the boundaries the triangles were inserted by, left the grid at x = lo in cell (0, 34, 24) before the ray
// crossed into (0, 34, 23), and missed triangle 278 there (5 of 67,496 spawned rays at 1e5 before the fix, 0
// after).
TEST(ScaleInvariance, GridWalkKeepsToTheInsertedCellBoundariesFarFromTheOrigin) {
  Scene box = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/meshes/subdivided_box.obj");
  Scene moved = transform_scene(box, kTransforms[2]);
  BruteForce brute;
  brute.build(moved.geometry);
  std::unique_ptr<Accelerator> grid = make_accelerator("grid");
  grid->build(moved.geometry);
  Ray r;  // a ray spawned just under the top face, grazing it
  r.origin = glm::vec3(0x1.869fb4p+16f, 0x1.86a074p+16f, 0x1.86a06cp+16f);
  r.direction = glm::vec3(-0x1.39c5dcp-1f, -0x1.062902p-10f, -0x1.949644p-1f);
  r.tmin = 0x1.00592p-2f;
  Hit a, b;
  ASSERT_TRUE(brute.intersect(r, &a));
  EXPECT_EQ(a.prim, 278);
  EXPECT_TRUE(grid->intersect(r, &b));
  EXPECT_EQ(b.prim, a.prim);
  EXPECT_EQ(b.t, a.t);
  // And rays from far away through a fine grid far from the origin: the drift grows with t's magnitude.
  std::vector<Ray> rays;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  for (int i = 0; i < 4000; ++i) {
    Ray f;
    f.origin = glm::vec3(1e5f) + 300.f * glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.f, 0.f, 400.f);
    f.direction = glm::vec3(1e5f) + glm::vec3(u(rng), u(rng), u(rng)) - f.origin;
    rays.push_back(f);
  }
  EXPECT_EQ(test::count_disagreements(*grid, brute, rays), 0);
}

// A point light within the offset of a sphere's tangent plane (the Cornell box's mirror sphere moved to 1e5:
// the offset is 0.04, the light 1.6 m away): the origin was moved to the side of to - p, the direction taken
// from the moved origin, which lay on the other side, and the shadow ray left from inside through its own
// sphere (1 self-hit of 67,496 spawned rays at 1e5, for every structure, before the fix).
TEST(ScaleInvariance, ShadowRayTowardsALightInTheTangentPlaneKeepsItsSide) {
  const Sphere s{glm::vec3(0x1.86a06cp+16f, 0x1.86a05ap+16f, 0x1.86a04cp+16f), 0.35f};
  const glm::vec3 p(0x1.86a01ap+16f, 0x1.86a05ap+16f, 0x1.86a07p+16f);
  const glm::vec3 err(gamma(2) * (glm::abs(s.center) + glm::abs(p)));
  const glm::vec3 n = glm::normalize(p - s.center);
  int self = 0, cast = 0;
  // Lights 1.5 away, from 3 degrees below the tangent plane to 3 above it.
  glm::vec3 tangent = glm::normalize(glm::cross(n, glm::vec3(0.f, 0.f, 1.f)));
  for (int i = -300; i <= 300; ++i) {
    float angle = float(i) * 1e-4f;
    glm::vec3 to = p + 1.5f * (std::cos(angle) * tangent + std::sin(angle) * n);
    Ray r = spawn_ray_to(p, err, n, to);
    float t;
    ++cast;
    if (intersect_sphere(r, s, r.tmax, &t)) {
      // Leaving outwards, any hit is the sphere again; inwards, the chord's far end is 2 r |cos| away, beyond
      // half of it.
      double len = glm::length(glm::dvec3(r.direction));
      double cos_out = glm::dot(glm::dvec3(r.direction), glm::dvec3(n)) / len;
      self += cos_out >= 0 || double(t) * len < -cos_out * double(s.radius);
    }
  }
  EXPECT_EQ(self, 0) << cast;
}

// GCC 12.2's SLP vectorizer drops the float rounding of a pair of double(float(x)) round trips made in one
// function (/work/notes/gcc12-slp-float-roundtrip.cpp; the BSP builder rounds out of line for it). The
// clipped bounds round each axis's lo and hi that way (triangle_clip.h: `float l = float(lo), h = float(hi);
// if (double(l) > lo) step down`), and nothing widens them after: a dropped rounding leaves a bound half an
// ulp inside the exact clip. The library's copy (inlined in kdtree_build.cpp, compiled -O3) must contain the
// exact rational clip and equal this translation unit's copy bit for bit.
TEST(ScaleInvariance, KdClippedBoundsContainTheExactClipAsTheLibraryCompiledThem) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-2.f, 2.f);
  int clipped = 0, outside = 0, differ = 0;
  for (float scale : {1e-6f, 1.f, 1e6f})
    for (int k = 0; k < 120; ++k) {
      Geometry g;
      g.begin_object("t", 0);
      glm::vec3 p[3];
      for (glm::vec3& v : p) v = scale * glm::vec3(u(rng), u(rng), u(rng));
      g.add_triangle(p[0], p[1], p[2]);
      Bounds3 box(scale * glm::vec3(u(rng), u(rng), u(rng)), scale * glm::vec3(u(rng), u(rng), u(rng)));
      Bounds3 lib = kd::clipped_bounds(g, 0, box);
      Bounds3 here = clip_triangle_bounds(p[0], p[1], p[2], box);
      for (int a = 0; a < 3; ++a)
        differ += !lib.empty() && (lib.lo[a] != here.lo[a] || lib.hi[a] != here.hi[a]);
      std::vector<test::QVec> exact = test::exact_clip(p[0], p[1], p[2], box);
      test::QVec lo, hi;
      if (!test::exact_bounds(exact, &lo, &hi)) continue;
      ++clipped;
      bool ok = !lib.empty();
      for (int a = 0; a < 3 && ok; ++a)
        ok = test::Q(double(lib.lo[a])) <= lo[a] && test::Q(double(lib.hi[a])) >= hi[a];
      outside += !ok;
    }
  EXPECT_GT(clipped, 100);
  EXPECT_EQ(outside, 0);
  EXPECT_EQ(differ, 0);
}

// ---- Part 2: a tiny triangle far from the origin ----

// Tiles a thousandth wide in the plane x = c (y and z near 0 keep their precision; x is c to the float), a
// tilted one that spans one ulp of c in x, tiles a few ulps wide at (c, c, c), a large floor near the origin
// that stretches the scene's box from 0 to c, and a scatter of small triangles between them, so that every
// structure builds a real tree whose boxes, planes and cells near the tiles are a thousandth wide at 1e5 or
// 1e6.
struct FarScene {
  Geometry g;
  std::vector<uint32_t> tiny;  // the far tiles
};

FarScene far_scene(float c) {
  FarScene s;
  const float w = 1e-3f, u = next_float_up(c) - c;
  s.g.begin_object("far tiles", 0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      glm::vec3 p(c, float(i) * w, float(j) * w);
      s.tiny.push_back(s.g.add_triangle(p, p + glm::vec3(0.f, w, 0.f), p + glm::vec3(0.f, 0.f, w)));
      s.tiny.push_back(
          s.g.add_triangle(p + glm::vec3(0.f, w, 0.f), p + glm::vec3(0.f, w, w), p + glm::vec3(0.f, 0.f, w)));
    }
  glm::vec3 q(c, -2 * w, -2 * w);
  s.tiny.push_back(s.g.add_triangle(q, q + glm::vec3(u, w, 0.f), q + glm::vec3(0.f, 0.f, w)));
  for (int k = 0; k < 4; ++k) {
    glm::vec3 r(c + float(k) * 4 * u, c, c);
    s.tiny.push_back(s.g.add_triangle(r, r + glm::vec3(2 * u, 0.f, u), r + glm::vec3(0.f, 2 * u, u)));
  }
  s.g.begin_object("floor", 0);
  s.g.add_triangle(glm::vec3(-10.f, -5.f, -10.f), glm::vec3(10.f, -5.f, -10.f), glm::vec3(0.f, -5.f, 10.f));
  s.g.begin_object("scatter", 0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> along(0.f, 1.f), side(-1.f, 1.f);
  for (int i = 0; i < 96; ++i) {
    glm::vec3 p(c * along(rng), 50.f + 20.f * side(rng), 50.f + 20.f * side(rng));
    s.g.add_triangle(p, p + glm::vec3(side(rng), side(rng), side(rng)),
                     p + glm::vec3(side(rng), side(rng), side(rng)));
  }
  return s;
}

TEST(ScaleInvariance, TinyTriangleFarFromTheOriginIsNeverCulled) {
  for (float c : {1e5f, 1e6f}) {
    FarScene s = far_scene(c);
    BruteForce brute;
    brute.build(s.g);
    // Rays aimed at points of the tiles (barycentric lattice, edges and vertices included, and just beyond),
    // from far away (near the origin: 1e5 or 1e6 units) and from nearby (1e-2 and 1 away, many directions).
    std::vector<Ray> rays;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (uint32_t id : s.tiny) {
      glm::dvec3 p0(s.g.vertex(id, 0)), p1(s.g.vertex(id, 1)), p2(s.g.vertex(id, 2));
      for (int i = -1; i <= 5; ++i)
        for (int j = -1; i + j <= 5; ++j) {
          glm::dvec3 target = p0 + (p1 - p0) * (double(i) / 4) + (p2 - p0) * (double(j) / 4);
          for (double dist : {-1.0, 1e-2, 1.0}) {
            Ray r;
            if (dist < 0) {
              r.origin = glm::vec3(float(unit(rng)), float(unit(rng)), float(unit(rng)));
            } else {
              glm::dvec3 dir = glm::normalize(glm::dvec3(-1.0, 0.5 * unit(rng), 0.5 * unit(rng)));
              if (id == s.tiny.back() || id + 4 >= s.tiny.back())
                dir = glm::normalize(glm::dvec3(-1.0, -1.0, -1.0) +
                                     0.3 * glm::dvec3(unit(rng), unit(rng), unit(rng)));
              r.origin = glm::vec3(target + dist * dir);
            }
            r.direction = glm::vec3(target - glm::dvec3(r.origin));
            rays.push_back(r);
          }
        }
    }
    // Brute force against the exact answer: whenever the exact line meets a tile, brute force reports a hit
    // no farther; whenever it reports a tile, the exact line meets it.
    int exact_hits = 0, wrong = 0;
    for (const Ray& r : rays) {
      Hit h;
      brute.intersect(r, &h);
      for (uint32_t id : s.tiny) {
        test::ExactHit e =
            test::exact_ray_triangle(r, s.g.vertex(id, 0), s.g.vertex(id, 1), s.g.vertex(id, 2));
        exact_hits += e.hit;
        if (e.hit && !(h.found() && test::Q(double(h.t)) <= e.t * test::Q(1.0 + 1e-6))) ++wrong;
        if (h.prim == int32_t(id) && !e.hit) ++wrong;
      }
    }
    EXPECT_GT(exact_hits, int(rays.size()) / 3) << c;
    EXPECT_EQ(wrong, 0) << c;
    for (const char* name : kStructures) {
      std::unique_ptr<Accelerator> accel = make_accelerator(name);
      accel->build(s.g);
      EXPECT_EQ(test::count_disagreements(*accel, brute, rays), 0) << c << " " << name;
    }
    std::printf("far %g: %zu rays, %d exact tile hits\n", double(c), rays.size(), exact_hits);
  }
}

}  // namespace
}  // namespace raystep
