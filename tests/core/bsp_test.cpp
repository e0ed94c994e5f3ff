// The general BSP tree's traversal: agreement with brute force (same primitive, same t) on random rays,
// camera rays (whole pictures), edge-aimed rays, rays lying in and starting on the tree's own slanted planes,
// +-0 components, NaN and infinite rays, slanted and pathological scenes; the recorded walk is the kernel's:
// every descent follows the plane's near/far rule, pushes are popped in order, and the recorded hit is the
// kernel's.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include <glm/geometric.hpp>

#include "raystep/accel/brute_force.h"
#include "raystep/accel/bsp.h"
#include "raystep/accel/structure_options.h"
#include "raystep/geometry/icosphere.h"
#include "raystep/render/render.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/io/scene_loader.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/record/event_recorder.h"
#include "raystep/util/error.h"
#include "ray_battery.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using test::count_disagreements;

std::unique_ptr<BspTree> make_bsp(const Geometry& g, BspOptions o = {}, bool mailboxes = true) {
  auto t = std::make_unique<BspTree>(o, mailboxes);
  t->build(g);
  return t;
}

const BspDirections kDirections[] = {BspDirections::both, BspDirections::kdop, BspDirections::autopartition};

// A box turned about a slanted axis, inside a second one turned the other way, and a few small ones.
Geometry make_rotated_boxes() {
  Geometry g;
  g.begin_object("boxes", 0);
  glm::mat4 m = glm::rotate(glm::mat4(1.f), glm::radians(33.f), glm::normalize(glm::vec3(1.f, 2.f, 0.5f)));
  add_mesh(g, make_box(glm::vec3(-1.f), glm::vec3(1.f, 2.f, 0.5f)), m);
  glm::mat4 m2 = glm::rotate(glm::mat4(1.f), glm::radians(-61.f), glm::normalize(glm::vec3(-1.f, 0.3f, 1.f)));
  add_mesh(g, make_box(glm::vec3(-3.f), glm::vec3(3.f)), m2);
  for (int i = 0; i < 8; ++i) {
    glm::vec3 lo(float(i % 2) - 2.5f, float(i / 2 % 2) - 0.5f, float(i / 4) + 0.7f);
    add_mesh(g, make_box(lo, lo + glm::vec3(0.3f)), m * m2);
  }
  return g;
}

// Thin triangles in one tilted plane, and a second tilted layer just above it.
Geometry make_tilted_plane(int n) {
  Geometry g;
  g.begin_object("tilted", 0);
  for (int layer = 0; layer < 2; ++layer) {
    const float a = glm::radians(27.f);
    glm::vec3 u(std::cos(a), 0.f, std::sin(a)), v(0.f, std::cos(0.3f), std::sin(0.3f)),
        w(0.f, 0.f, 0.01f * layer);
    for (int i = 0; i < n; ++i) {
      float x = float(i % 40) * 0.25f, y = float(i / 40) * 0.25f;
      g.add_triangle(x * u + y * v + w, (x + 0.24f) * u + y * v + w, (x + 0.02f) * u + (y + 0.24f) * v + w);
    }
  }
  return g;
}

TEST(Bsp, AgreesWithBruteForceOnRandomRays) {
  for (int spheres : {8, 0}) {
    Geometry g = test::make_soup(41, 400, spheres);
    BruteForce brute;
    brute.build(g);
    std::vector<Ray> rays = random_rays(g.bounds(), 15000, 42);
    for (BspDirections dirs : kDirections)
      for (bool mailboxes : {true, false}) {
        BspOptions o;
        o.directions = dirs;
        auto tree = make_bsp(g, o, mailboxes);
        EXPECT_GT(tree->data().nodes.size(), 20u);
        EXPECT_EQ(count_disagreements(*tree, brute, rays), 0)
            << bsp_directions_name(dirs) << " mailboxes " << mailboxes << " spheres " << spheres;
      }
  }
}

TEST(Bsp, AgreesWithBruteForceUnderEveryOption) {
  Geometry g = test::make_soup(43, 200, 4);
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = random_rays(g.bounds(), 10000, 44);
  std::vector<BspOptions> variants(5);
  variants[0].candidates = 1;
  variants[1].candidates = 200;
  variants[2].max_depth = 3;
  variants[3].leaf_size = 8;
  variants[4].t_i = 2.f;
  variants[4].t_t = 5.f;
  for (size_t v = 0; v < variants.size(); ++v)
    EXPECT_EQ(count_disagreements(*make_bsp(g, variants[v]), brute, rays), 0) << "variant " << v;
}

// Rays tied to the tree's own planes: lying in a plane (direction = normal x random), starting on it,
// along the plane normal, and axis-parallel with +0 and -0 on the other axes through a node's cell.
std::vector<Ray> plane_rays(const BspTree& tree, uint32_t seed) {
  const BspTreeData& d = tree.data();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::normal_distribution<float> n;
  std::vector<Ray> rays;
  for (size_t id = 0; id < d.nodes.size(); ++id) {
    const BspNode& node = d.nodes[id];
    if (node.is_leaf()) continue;
    const Bounds3& box = d.info[id].box;
    const glm::vec3 nn = node.plane.normal;
    for (int k = 0; k < 6; ++k) {
      glm::vec3 p = box.lo + box.extent() * glm::vec3(u(rng), u(rng), u(rng));
      // Onto the plane (within float rounding: the ray lies in it as closely as floats allow).
      p -= (glm::dot(nn, p) - node.plane.offset) * nn;
      Ray r;
      r.origin = p;
      if (k < 2) r.direction = glm::cross(nn, glm::vec3(n(rng), n(rng), n(rng)));  // in the plane
      if (k == 2) r.direction = u(rng) < 0.5f ? nn : -nn;                          // across it, from on it
      if (k == 3) r.direction = glm::vec3(n(rng), n(rng), n(rng));                 // from on it
      if (k == 4) {  // axis-parallel with signed zeros
        r.direction = glm::vec3(u(rng) < 0.5f ? 0.f : -0.f, u(rng) < 0.5f ? 0.f : -0.f, -0.f);
        r.direction[int(id % 3)] = u(rng) < 0.5f ? 1.f : -1.f;
      }
      if (k == 5) {  // corner to corner of the cell's box
        r.origin = box.lo;
        r.direction = box.hi - box.lo;
      }
      rays.push_back(r);
    }
  }
  return rays;
}

TEST(Bsp, SlantedScenesWithHardRays) {
  for (int scene = 0; scene < 2; ++scene) {
    Geometry g = scene == 0 ? make_rotated_boxes() : make_tilted_plane(400);
    BruteForce brute;
    brute.build(g);
    std::vector<Ray> random = random_rays(g.bounds(), 8000, 45);
    for (BspDirections dirs : kDirections) {
      BspOptions o;
      o.directions = dirs;
      auto tree = make_bsp(g, o);
      std::vector<Ray> rays = plane_rays(*tree, 46);
      ASSERT_GT(rays.size(), 60u);
      EXPECT_EQ(count_disagreements(*tree, brute, rays), 0)
          << "scene " << scene << " " << bsp_directions_name(dirs);
      EXPECT_EQ(count_disagreements(*tree, brute, random), 0)
          << "scene " << scene << " " << bsp_directions_name(dirs);
    }
  }
}

TEST(Bsp, NoFixedEpsilonAtLargeOrSmallScale) {
  // The same slanted scene far from the origin and large, and tiny: every bound is relative to the numbers.
  const Geometry base = make_rotated_boxes();
  for (auto [scale, offset] : {std::pair{1e4f, 1e6f}, std::pair{1e-5f, 0.f}, std::pair{1e-3f, 3e-2f}}) {
    Geometry g;
    g.begin_object("scaled", 0);
    for (uint32_t i = 0; i < base.size(); ++i)
      g.add_triangle(base.vertex(i, 0) * scale + offset, base.vertex(i, 1) * scale + offset,
                     base.vertex(i, 2) * scale + offset);
    BruteForce brute;
    brute.build(g);
    auto tree = make_bsp(g);
    EXPECT_GT(tree->data().nodes.size(), 50u) << scale;
    std::vector<Ray> rays = random_rays(g.bounds(), 6000, 55), hard = plane_rays(*tree, 56);
    rays.insert(rays.end(), hard.begin(), hard.end());
    EXPECT_EQ(count_disagreements(*tree, brute, rays), 0) << "scale " << scale << " offset " << offset;
  }
}

TEST(Bsp, WatertightOnEdgeAimedRays) {
  Geometry g;
  add_to_geometry(make_icosphere(3), g);
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = edge_rays(g, 15000, 47);
  for (BspDirections dirs : kDirections) {
    BspOptions o;
    o.directions = dirs;
    auto tree = make_bsp(g, o);
    EXPECT_EQ(count_disagreements(*tree, brute, rays), 0) << bsp_directions_name(dirs);
    EXPECT_EQ(test::count_leaks(*tree, rays, 5000), 0) << bsp_directions_name(dirs);
  }
}

TEST(Bsp, PathologicalScenes) {
  std::vector<Geometry> scenes;
  {
    Geometry g;
    g.begin_object("identical", 0);
    for (int i = 0; i < 400; ++i)
      g.add_triangle(glm::vec3(0.f), glm::vec3(1.f, 0.f, 0.2f), glm::vec3(0.f, 1.f, 0.4f));
    g.add_triangle(glm::vec3(-1.f, -1.f, 1.f), glm::vec3(2.f, -1.f, 1.f), glm::vec3(-1.f, 2.f, 1.f));
    scenes.push_back(std::move(g));
  }
  {
    Geometry g;
    g.begin_object("coplanar", 0);
    std::mt19937 rng(48);
    std::uniform_real_distribution<float> u(0.f, 10.f), s(0.05f, 0.5f);
    for (int i = 0; i < 400; ++i) {
      glm::vec3 p(u(rng), u(rng), 0.5f);
      g.add_triangle(p, p + glm::vec3(s(rng), 0.f, 0.f), p + glm::vec3(0.f, s(rng), 0.f));
    }
    add_mesh(g, make_box(glm::vec3(2.f, 2.f, -1.f), glm::vec3(3.f, 3.f, 2.f)), glm::mat4(1.f));
    scenes.push_back(std::move(g));
  }
  {
    Geometry g;
    g.begin_object("slivers", 0);
    std::mt19937 rng(49);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    for (int i = 0; i < 300; ++i) {
      glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
      g.add_triangle(10.f * a, -10.f * a, 10.f * a + 1e-3f * b);
    }
    scenes.push_back(std::move(g));
  }
  for (size_t s = 0; s < scenes.size(); ++s) {
    const Geometry& g = scenes[s];
    BruteForce brute;
    brute.build(g);
    auto tree = make_bsp(g);
    std::vector<Ray> rays = random_rays(g.bounds(), 30000, 50), hard = plane_rays(*tree, 51);
    rays.insert(rays.end(), hard.begin(), hard.end());
    for (int i = 0; i < 200; ++i) {  // straight down onto the coplanar set, and grazing along its plane
      Ray r;
      r.origin = glm::vec3(0.05f * float(i), 0.037f * float(i), 3.f);
      r.direction = glm::vec3(0.f, -0.f, -1.f);
      rays.push_back(r);
      r.origin.z = 0.5f;
      r.direction = glm::vec3(1.f, 0.3f, 0.f);
      rays.push_back(r);
    }
    EXPECT_EQ(count_disagreements(*tree, brute, rays), 0) << "scene " << s;
  }
}

TEST(Bsp, NonFiniteRaysMissAndTerminate) {
  Geometry g = test::make_soup(52, 50, 1);
  auto tree = make_bsp(g);
  EXPECT_EQ(test::count_non_finite_hits(*tree), 0);
  float nan = std::nanf(""), inf = kInfinity;
  // NaN and infinite tmax/tmin.
  Ray r;
  r.origin = glm::vec3(-5.f, 0.1f, 0.2f);
  r.direction = glm::vec3(1.f, 0.f, 0.f);
  r.tmax = nan;
  Hit h;
  EXPECT_FALSE(tree->intersect(r, &h));
  r.tmax = inf;
  r.tmin = -inf;
  BruteForce brute;
  brute.build(g);
  Hit a;
  EXPECT_EQ(tree->intersect(r, &h), brute.intersect(r, &a));
  EXPECT_EQ(h.prim, a.prim);
}

TEST(Bsp, EmptySceneAndFactory) {
  Geometry empty;
  auto tree = make_bsp(empty);
  Ray r;
  Hit h;
  EXPECT_FALSE(tree->intersect(r, &h));
  EXPECT_EQ(make_accelerator("bsp")->name(), "bsp");
  auto names = accelerator_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "bsp"), names.end());
  StructureOptions bad;
  bad.bsp.candidates = 0;
  Geometry g = test::make_soup(1, 10, 0);
  EXPECT_THROW(make_accelerator("bsp", bad)->build(g), InputError);
}

// The recorded walk is the kernel's, decision by decision, on a slanted scene: each descent goes to a child
// of the node before it, the one bsp_crossing names (near if the plane is not reached, far if crossed before
// the node, near then far pushed if crossed inside); pushes and pops pair up; intervals shrink; the recorded
// hit is the unrecorded kernel's.
TEST(Bsp, RecordedWalkIsTheKernels) {
  Geometry g = make_rotated_boxes();
  g.begin_object("soup", 0);
  Geometry soup = test::make_soup(53, 200, 0);
  for (uint32_t i = 0; i < soup.size(); ++i)
    g.add_triangle(soup.vertex(i, 0), soup.vertex(i, 1), soup.vertex(i, 2));
  auto tree = make_bsp(g);
  const BspTreeData& d = tree->data();
  std::vector<Ray> rays = random_rays(g.bounds(), 600, 54);
  EventRecorder rec;
  int pushes = 0, descents = 0;
  for (const Ray& r : rays) {
    rec.clear();
    Hit hit, plain;
    bool found = tree->traverse(r, &hit, false, rec);
    tree->intersect(r, &plain);
    EXPECT_EQ(hit.prim, plain.prim);
    EXPECT_EQ(hit.t, plain.t);
    const std::vector<Event>& ev = rec.events();
    ASSERT_EQ(ev.front().type, EventType::ray_begin);
    ASSERT_EQ(ev.back().type, EventType::ray_end);
    EXPECT_EQ(ev.back().prim, hit.prim);
    std::vector<Event> stack;
    const Event* last_node = nullptr;
    const Event* pending_push = nullptr;
    for (const Event& e : ev) {
      if (e.type == EventType::node) {
        EXPECT_LE(e.t_min_node, e.t_max_node);
        EXPECT_EQ(e.depth, d.info[size_t(e.node)].depth);
        if (last_node) {
          // A descent from last_node: check the kernel's rule.
          const BspNode& parent = d.nodes[size_t(last_node->node)];
          ASSERT_FALSE(parent.is_leaf());
          BspCrossing c =
              bsp_crossing(parent.plane, r.origin, r.direction,
                           std::max(std::fabs(last_node->t_min_node), std::fabs(last_node->t_max_node)));
          uint32_t below = uint32_t(last_node->node) + 1, above = parent.above_child();
          uint32_t near_child = c.below_first ? below : above, far_child = c.below_first ? above : below;
          if (pending_push) {
            EXPECT_EQ(uint32_t(e.node), near_child);
            EXPECT_EQ(uint32_t(pending_push->node), far_child);
          } else {
            EXPECT_TRUE(uint32_t(e.node) == near_child || uint32_t(e.node) == far_child);
          }
          EXPECT_GE(e.t_min_node, last_node->t_min_node);
          EXPECT_LE(e.t_max_node, last_node->t_max_node);
          ++descents;
        }
        last_node = d.nodes[size_t(e.node)].is_leaf() ? nullptr : &e;
        pending_push = nullptr;
      } else if (e.type == EventType::push) {
        stack.push_back(e);
        pending_push = &stack.back();
        ++pushes;
      } else if (e.type == EventType::pop) {
        ASSERT_FALSE(stack.empty());
        EXPECT_EQ(stack.back().node, e.node);
        EXPECT_EQ(stack.back().t_min_node, e.t_min_node);
        EXPECT_EQ(stack.back().t_max_node, e.t_max_node);
        stack.pop_back();
        last_node = nullptr;
      }
    }
    if (!found) EXPECT_TRUE(stack.empty());
  }
  EXPECT_GT(pushes, 100);
  EXPECT_GT(descents, 1000);
}

TEST(Bsp, RendersTheSamePictureAsBruteForce) {
  for (const char* name : {"spheres.json", "cornell.json"}) {
    Scene scene = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/" + name);
    RenderOptions opt = render_options(scene.render);
    opt.width = 64;
    opt.height = 48;
    BruteForce brute;
    brute.build(scene.geometry);
    Image reference = render_image(scene, brute, opt).image;
    auto tree = make_bsp(scene.geometry);
    Image image = render_image(scene, *tree, opt).image;
    EXPECT_TRUE(image.pixels == reference.pixels) << name;
  }
}

}  // namespace
}  // namespace raystep
