#include "raystep/accel/kdtree_entry_probability.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "raystep/render/sampler.h"

namespace raystep {

namespace {

// Counts the nodes a real traversal visits, and its primitive tests.
struct NodeVisitCounter : NullRecorder {
  std::vector<uint32_t>* counts;
  uint64_t prim_tests = 0;
  void node(const TreeStep& s) { ++(*counts)[size_t(s.node)]; }
  void prim_test(uint32_t, bool, float) { ++prim_tests; }
};

// Every node whose box the line crosses: the children of a crossed node whose boxes it meets.
void cross(const KdTreeData& tree, const SlabRay& line, uint32_t id, std::vector<uint32_t>& counts) {
  for (;;) {
    ++counts[id];
    const KdNode& n = tree.nodes[id];
    if (n.is_leaf()) return;
    uint32_t below = id + 1, above = n.above_child();
    bool hit_below = intersect_slabs(tree.info[below].box, line, nullptr, nullptr);
    bool hit_above = intersect_slabs(tree.info[above].box, line, nullptr, nullptr);
    if (hit_below && hit_above) cross(tree, line, above, counts);
    if (hit_below) id = below;
    else if (hit_above) id = above;
    else return;
  }
}

}  // namespace

std::vector<KdNodeEntry> measure_entry_probability(const KdTree& tree, size_t lines, uint64_t seed,
                                                   size_t* rays_cast, uint64_t max_ray_tests) {
  const KdTreeData& data = tree.data();
  std::vector<KdNodeEntry> out(data.nodes.size());
  if (rays_cast) *rays_cast = 0;
  if (data.nodes.empty() || data.bounds.empty()) return out;
  // Every line through the root enters the root; below a root of zero area (a point, a segment) the ratio is
  // 0/0 and says nothing.
  double s_root = data.bounds.surface_area();
  for (size_t i = 0; i < out.size(); ++i)
    out[i].predicted = i == 0       ? 1.0
                       : s_root > 0 ? double(data.info[i].box.surface_area()) / s_root
                                    : std::nan("");

  std::vector<uint32_t> crossed(out.size(), 0), entered(out.size(), 0);
  NodeVisitCounter counter;
  counter.counts = &entered;
  glm::vec3 centre = data.bounds.center();
  float radius = 0.5f * glm::length(data.bounds.extent());
  Pcg32 rng(seed, 0);
  size_t kept = 0, cast = 0;
  for (size_t attempts = 0; kept < lines && attempts < 64 * lines; ++attempts) {
    // An isotropic direction, and an offset uniform on the disc of the bounding sphere perpendicular to it.
    float z = 1.f - 2.f * rng.uniform(), phi = 6.2831853f * rng.uniform();
    float s = std::sqrt(std::max(0.f, 1.f - z * z));
    glm::vec3 d(s * std::cos(phi), s * std::sin(phi), z);
    glm::vec3 axis = std::fabs(d.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    glm::vec3 u = glm::normalize(glm::cross(d, axis));
    glm::vec3 v = glm::cross(d, u);
    float r = radius * std::sqrt(rng.uniform()), a = 6.2831853f * rng.uniform();
    Ray ray;
    ray.origin = centre + r * (std::cos(a) * u + std::sin(a) * v) - 2.f * radius * d;
    ray.direction = d;
    SlabRay line(ray);
    if (!intersect_slabs(data.bounds, line, nullptr, nullptr)) continue;
    ++kept;
    cross(data, line, 0, crossed);
    // The rays test primitives, lines do not: on a leaf of 100,000 identical triangles every ray tests them
    // all, so the rays stop after max_ray_tests tests in all and their fraction is over the rays cast.
    if (counter.prim_tests < max_ray_tests) {
      Hit hit;
      tree.traverse(ray, &hit, false, counter);
      ++cast;
    }
  }
  for (size_t i = 0; i < out.size() && kept; ++i) {
    out[i].lines = double(crossed[i]) / double(kept);
    out[i].rays = cast ? double(entered[i]) / double(cast) : 0.0;
  }
  if (rays_cast) *rays_cast = cast;
  return out;
}

}  // namespace raystep
