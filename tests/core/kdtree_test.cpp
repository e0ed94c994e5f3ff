// The kd-tree's traversal: agreement with brute force (same primitive, same t) on random rays and on the hard
// ones (axis-parallel with +0 and -0, rays lying in split planes, origins on planes, faces on candidate
// planes, coplanar and identical triangles, edge-aimed rays), and the recorded walk's invariants (every push
// popped or the walk ended on a hit, intervals shrinking down the tree, each primitive tested once with
// mailboxes).
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "ray_battery.h"
#include "raystep/accel/brute_force.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/kdtree_entry_probability.h"
#include "raystep/accel/structure_options.h"
#include "raystep/geometry/icosphere.h"
#include "raystep/io/scene_loader.h"
#include "raystep/record/event_recorder.h"
#include "raystep/render/render.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/util/error.h"
#include "test_budget.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using test::make_soup;

// Axis-aligned boxes on a lattice: their faces lie on each other's candidate planes, many are coplanar.
Geometry make_boxes() {
  Geometry g;
  g.begin_object("boxes", 0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      glm::vec3 lo(float(i), float(j), float((i + j) % 2));
      add_mesh(g, make_box(lo, lo + glm::vec3(1.f, 1.f, 1.f + float(i))), glm::mat4(1.f));
    }
  return g;
}

// n triangles in the plane z = 0.5, tiling a square.
Geometry make_coplanar(int n) {
  Geometry g;
  g.begin_object("coplanar", 0);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.f, 10.f), s(0.05f, 0.5f);
  for (int i = 0; i < n; ++i) {
    glm::vec3 p(u(rng), u(rng), 0.5f);
    g.add_triangle(p, p + glm::vec3(s(rng), 0.f, 0.f), p + glm::vec3(0.f, s(rng), 0.f));
  }
  // Something off the plane, so that the scene has depth.
  add_mesh(g, make_box(glm::vec3(2.f, 2.f, -1.f), glm::vec3(3.f, 3.f, 2.f)), glm::mat4(1.f));
  return g;
}

Geometry make_identical(int n) {
  Geometry g;
  g.begin_object("identical", 0);
  for (int i = 0; i < n; ++i)
    g.add_triangle(glm::vec3(0.f), glm::vec3(1.f, 0.f, 0.2f), glm::vec3(0.f, 1.f, 0.4f));
  g.add_triangle(glm::vec3(-1.f, -1.f, 1.f), glm::vec3(2.f, -1.f, 1.f), glm::vec3(-1.f, 2.f, 1.f));
  return g;
}

std::unique_ptr<KdTree> make_tree(const Geometry& g, KdBuilder builder, bool mailboxes = true,
                                  KdOptions options = {}) {
  options.builder = builder;
  auto tree = std::make_unique<KdTree>(options, mailboxes);
  tree->build(g);
  return tree;
}

using test::count_disagreements;

const KdBuilder kBuilders[] = {KdBuilder::sah, KdBuilder::median};

TEST(KdTree, AgreesWithBruteForceOnRandomRays) {
  // A soup with spheres and one of triangles only.
  for (int spheres : {8, 0}) {
    Geometry g = make_soup(5, 400, spheres);
    BruteForce brute;
    brute.build(g);
    std::vector<Ray> rays = random_rays(g.bounds(), test::budget(100000), 9);
    for (KdBuilder builder : kBuilders)
      for (bool mailboxes : {true, false}) {
        auto tree = make_tree(g, builder, mailboxes);
        EXPECT_GT(tree->data().nodes.size(), 1u);
        EXPECT_EQ(count_disagreements(*tree, brute, rays), 0)
            << "builder " << int(builder) << " mailboxes " << mailboxes << " spheres " << spheres;
        // The barycentrics too, bit for bit.
        for (size_t i = 0; i < rays.size(); i += 7) {
          Hit a, b;
          if (!brute.intersect(rays[i], &a)) continue;
          tree->intersect(rays[i], &b);
          EXPECT_EQ(a.b1, b.b1);
          EXPECT_EQ(a.b2, b.b2);
        }
      }
  }
}

TEST(KdTree, AgreesWithBruteForceUnderEveryOption) {
  Geometry g = make_soup(6, 200, 4);
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = random_rays(g.bounds(), 20000, 10);
  std::vector<KdOptions> variants(5);
  variants[0].empty_bonus = 0.5f;
  variants[1].leaf_size = 8;
  variants[2].max_depth = 3;
  variants[3].t_i = 2.f;
  variants[3].t_t = 5.f;
  variants[4].t_i = 1000.f;
  for (size_t v = 0; v < variants.size(); ++v)
    for (KdBuilder builder : kBuilders)
      EXPECT_EQ(count_disagreements(*make_tree(g, builder, true, variants[v]), brute, rays), 0)
          << "variant " << v << " builder " << int(builder);
}

TEST(KdTree, WatertightOnEdgeAimedRays) {
  // A closed icosphere; rays aimed exactly at shared edges and vertices, from outside and inside.
  Geometry g;
  add_to_geometry(make_icosphere(3), g);
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = edge_rays(g, test::budget(100000), 12);
  for (KdBuilder builder : kBuilders) {
    auto tree = make_tree(g, builder);
    EXPECT_EQ(count_disagreements(*tree, brute, rays), 0) << int(builder);
    // From the centre outwards every ray must hit: no leak between the leaves.
    EXPECT_EQ(test::count_leaks(*tree, rays, test::budget(20000)), 0) << int(builder);
  }
}

// Rays along the split planes of the tree itself: lying in them (direction component +0 or -0 on the axis),
// starting on them, axis-parallel with signed zeros, and through node corners.
std::vector<Ray> plane_rays(const KdTree& tree, uint32_t seed) {
  const KdTreeData& d = tree.data();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::normal_distribution<float> n;
  std::vector<Ray> rays;
  Bounds3 b = d.bounds;
  glm::vec3 lo = b.lo - 0.25f * b.extent(), e = 1.5f * b.extent();
  for (size_t id = 0; id < d.nodes.size(); ++id) {
    const KdNode& node = d.nodes[id];
    if (node.is_leaf()) continue;
    int axis = node.axis();
    const Bounds3& box = d.info[id].box;
    for (int k = 0; k < 6; ++k) {
      Ray r;
      r.origin = lo + e * glm::vec3(u(rng), u(rng), u(rng));
      r.origin[axis] = node.split;
      r.direction = glm::vec3(n(rng), n(rng), n(rng));
      if (k < 2) r.direction[axis] = k == 0 ? 0.f : -0.f;  // lying in the plane
      if (k == 2) {                                        // axis-parallel in the plane, through the node
        r.direction = glm::vec3(0.f);
        r.direction[(axis + 1) % 3] = u(rng) < 0.5f ? 1.f : -1.f;
        r.origin[(axis + 2) % 3] = box.lo[(axis + 2) % 3];  // on a node face too
      }
      if (k == 3) {  // axis-parallel across the plane, with -0 on the other axes
        r.direction = glm::vec3(-0.f);
        r.direction[axis] = u(rng) < 0.5f ? 1.f : -1.f;
        r.origin[axis] = u(rng) < 0.5f ? b.lo[axis] - 1.f : b.hi[axis] + 1.f;
      }
      if (k == 4) {  // from a corner of the node's box to the opposite corner
        r.origin = box.lo;
        r.direction = box.hi - box.lo;
        r.origin[axis] = node.split;
      }
      rays.push_back(r);
    }
  }
  return rays;
}

TEST(KdTree, HardRaysOnBoxesWhoseFacesAreCandidatePlanes) {
  Geometry g = make_boxes();
  BruteForce brute;
  brute.build(g);
  for (KdBuilder builder : kBuilders) {
    auto tree = make_tree(g, builder);
    std::vector<Ray> rays = plane_rays(*tree, 3);
    ASSERT_GT(rays.size(), 30u);
    // Neighbouring boxes share faces: coincident triangles are hit at the same t, either may be reported.
    EXPECT_EQ(count_disagreements(*tree, brute, rays), 0) << int(builder);
    std::vector<Ray> random = random_rays(g.bounds(), 100000, 13);
    EXPECT_EQ(count_disagreements(*tree, brute, random), 0) << int(builder);
  }
}

TEST(KdTree, CoplanarAndIdenticalTriangles) {
  for (int scene = 0; scene < 2; ++scene) {
    Geometry g = scene == 0 ? make_coplanar(400) : make_identical(400);
    BruteForce brute;
    brute.build(g);
    std::vector<Ray> random = random_rays(g.bounds(), test::budget(100000), 14);
    for (KdBuilder builder : kBuilders) {
      auto tree = make_tree(g, builder);
      std::vector<Ray> rays = random, hard = plane_rays(*tree, 5);
      rays.insert(rays.end(), hard.begin(), hard.end());
      // Rays straight down onto the plane of the coplanar set, and grazing along it.
      for (int i = 0; i < 200; ++i) {
        Ray r;
        r.origin = glm::vec3(0.05f * float(i), 0.037f * float(i), 3.f);
        r.direction = glm::vec3(0.f, -0.f, -1.f);
        rays.push_back(r);
        r.origin.z = 0.5f;
        r.direction = glm::vec3(1.f, 0.3f, 0.f);
        rays.push_back(r);
      }
      EXPECT_EQ(count_disagreements(*tree, brute, rays), 0) << "scene " << scene << " " << int(builder);
    }
  }
}

TEST(KdTree, NonFiniteRaysMissAndTerminate) {
  Geometry g = make_soup(8, 50, 1);
  auto tree = make_tree(g, KdBuilder::sah);
  EXPECT_EQ(test::count_non_finite_hits(*tree), 0);
}

TEST(KdTree, EmptySceneAndFactory) {
  Geometry empty;
  auto tree = make_tree(empty, KdBuilder::sah);
  Ray r;
  Hit h;
  EXPECT_FALSE(tree->intersect(r, &h));
  EXPECT_EQ(make_accelerator("kd")->name(), "kd");
  EXPECT_EQ(make_accelerator("kd-median")->name(), "kd-median");
  StructureOptions bad;
  bad.kd.t_i = -1.f;
  Geometry g = make_soup(1, 10, 0);
  EXPECT_THROW(make_accelerator("kd", bad)->build(g), InputError);
}

// The recorded walk of many rays: intervals shrink down the tree, every push is popped unless the walk ended
// on a hit, popped entries are the pushed ones, and with mailboxes no primitive is tested twice.
TEST(KdTree, RecordedWalkInvariants) {
  Geometry g = make_soup(9, 300, 4);
  for (KdBuilder builder : kBuilders) {
    auto tree = make_tree(g, builder);
    const KdTreeData& d = tree->data();
    std::vector<Ray> rays = random_rays(g.bounds(), 3000, 15);
    EventRecorder rec;
    int pushes = 0;
    for (const Ray& r : rays) {
      rec.clear();
      Hit hit;
      bool found = tree->traverse(r, &hit, false, rec);
      const std::vector<Event>& ev = rec.events();
      ASSERT_EQ(ev.front().type, EventType::ray_begin);
      ASSERT_EQ(ev.back().type, EventType::ray_end);
      std::vector<Event> stack;
      std::map<int32_t, int> tested;
      const Event* last_node = nullptr;
      for (const Event& e : ev) {
        if (e.type == EventType::node) {
          EXPECT_LE(e.t_min_node, e.t_max_node);
          if (last_node && d.info[size_t(e.node)].parent == last_node->node) {
            // A child on the descent: its interval lies inside its parent's.
            EXPECT_GE(e.t_min_node, last_node->t_min_node);
            EXPECT_LE(e.t_max_node, last_node->t_max_node);
            EXPECT_EQ(e.depth, last_node->depth + 1);
          }
          EXPECT_EQ(e.depth, d.info[size_t(e.node)].depth);
          last_node = &e;
        } else if (e.type == EventType::push) {
          stack.push_back(e);
          ++pushes;
        } else if (e.type == EventType::pop) {
          ASSERT_FALSE(stack.empty());
          EXPECT_EQ(stack.back().node, e.node);
          EXPECT_EQ(stack.back().t_min_node, e.t_min_node);
          EXPECT_EQ(stack.back().t_max_node, e.t_max_node);
          stack.pop_back();
          last_node = nullptr;
        } else if (e.type == EventType::prim_test) {
          EXPECT_EQ(++tested[e.prim], 1) << "primitive " << e.prim << " tested twice";
        }
      }
      if (!found) EXPECT_TRUE(stack.empty()) << "a miss must have popped every push";
      EXPECT_EQ(ev.back().prim, hit.prim);
    }
    EXPECT_GT(pushes, 100) << "the rays should cross split planes";
  }
}

TEST(KdTree, CountedQueriesGiveTheSameHits) {
  Geometry g = make_soup(10, 300, 2);
  auto tree = make_tree(g, KdBuilder::sah);
  std::vector<Ray> rays = random_rays(g.bounds(), 2000, 16);
  CountingRecorder counters;
  for (const Ray& r : rays) {
    Hit a, b;
    tree->intersect(r, &a);
    tree->intersect_counted(r, &b, counters);
    EXPECT_EQ(a.prim, b.prim);
    EXPECT_EQ(a.t, b.t);
  }
  EXPECT_EQ(counters.rays, rays.size());
  EXPECT_GT(counters.nodes, counters.rays);
  EXPECT_GE(counters.pushes, counters.pops);  // a walk that ends on a hit may leave entries on the stack
  EXPECT_GT(counters.prim_tests, 0u);
}

// The whole tracer (shadow, mirror and glass rays) gives the same picture, bit for bit, with either kd-tree
// as with brute force.
TEST(KdTree, RendersTheSamePictureAsBruteForce) {
  for (const char* name : {"spheres.json", "cornell.json"}) {
    Scene scene = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/" + name);
    RenderOptions opt = render_options(scene.render);
    opt.width = 64;
    opt.height = 48;
    BruteForce brute;
    brute.build(scene.geometry);
    Image reference = render_image(scene, brute, opt).image;
    for (KdBuilder builder : kBuilders) {
      auto tree = make_tree(scene.geometry, builder);
      Image image = render_image(scene, *tree, opt).image;
      EXPECT_TRUE(image.pixels == reference.pixels) << name << " builder " << int(builder);
    }
  }
}

// Crofton's theorem measured: every line through the root enters it, a child's fraction of the lines is near
// S_child / S_root, and the rays (which test primitives) stop after the test budget on a crowded leaf.
TEST(KdEntryProbability, LinesFollowCroftonAndRaysStopAtTheTestBudget) {
  Geometry g;
  add_to_geometry(make_icosphere(2), g);  // 320 triangles
  KdTree tree;
  tree.build(g);
  size_t cast = 0;
  std::vector<KdNodeEntry> e = measure_entry_probability(tree, 20000, 3, &cast);
  ASSERT_EQ(e.size(), tree.data().nodes.size());
  EXPECT_EQ(cast, 20000u);
  EXPECT_EQ(e[0].predicted, 1.0);
  EXPECT_EQ(e[0].lines, 1.0);
  EXPECT_EQ(e[0].rays, 1.0);
  for (size_t i = 1; i < std::min<size_t>(e.size(), 16); ++i) {
    EXPECT_NEAR(e[i].lines, e[i].predicted, 0.02) << "node " << i;
    EXPECT_LE(e[i].rays, e[i].lines + 0.02) << "node " << i;  // a ray stops at its first hit
  }

  // 2,000 identical triangles make one leaf, and every ray tests all of them: with a budget of 20,000 tests
  // the rays stop after 10, while all the lines are measured.
  Geometry crowd;
  for (int i = 0; i < 2000; ++i)
    crowd.add_triangle(glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 1));
  KdTree leaf;
  leaf.build(crowd);
  ASSERT_EQ(leaf.data().nodes.size(), 1u);
  std::vector<KdNodeEntry> c = measure_entry_probability(leaf, 500, 3, &cast, 20000);
  EXPECT_EQ(cast, 10u);
  EXPECT_EQ(c[0].lines, 1.0);
  EXPECT_EQ(c[0].rays, 1.0);

  // A root of zero area (all vertices at one point): the root is still entered with probability 1.
  Geometry point;
  point.add_triangle(glm::vec3(1, 2, 3), glm::vec3(1, 2, 3), glm::vec3(1, 2, 3));
  KdTree dot;
  dot.build(point);
  std::vector<KdNodeEntry> p = measure_entry_probability(dot, 100, 3, &cast);
  EXPECT_EQ(p[0].predicted, 1.0);
}

}  // namespace
}  // namespace raystep
