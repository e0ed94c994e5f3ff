#include "raystep/accel/bvh_entry_probability.h"

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

// Every node whose box the line crosses: the children of a crossed node whose boxes it meets (both may be).
void cross(const BvhData& bvh, const SlabRay& line, uint32_t id, std::vector<uint32_t>& counts) {
  for (;;) {
    ++counts[id];
    const BvhNode& n = bvh.nodes[id];
    if (n.is_leaf()) return;
    uint32_t left = id + 1, right = n.second_child();
    bool hit_left = intersect_slabs(bvh.nodes[left].box, line, nullptr, nullptr);
    bool hit_right = intersect_slabs(bvh.nodes[right].box, line, nullptr, nullptr);
    if (hit_left && hit_right) cross(bvh, line, right, counts);
    if (hit_left)
      id = left;
    else if (hit_right)
      id = right;
    else
      return;
  }
}

}  // namespace

std::vector<BvhNodeEntry> measure_bvh_entry_probability(const Bvh& bvh, size_t lines, uint64_t seed,
                                                        size_t* rays_cast, uint64_t max_ray_tests) {
  const BvhData& data = bvh.data();
  std::vector<BvhNodeEntry> out(data.nodes.size());
  if (rays_cast) *rays_cast = 0;
  if (data.nodes.empty() || data.nodes[0].box.empty()) return out;
  const Bounds3& root = data.nodes[0].box;
  double s_root = root.surface_area();
  for (size_t i = 0; i < out.size(); ++i)
    out[i].predicted = i == 0       ? 1.0
                       : s_root > 0 ? double(data.nodes[i].box.surface_area()) / s_root
                                    : std::nan("");

  std::vector<uint32_t> crossed(out.size(), 0), entered(out.size(), 0);
  NodeVisitCounter counter;
  counter.counts = &entered;
  glm::vec3 centre = root.center();
  float radius = 0.5f * glm::length(root.extent());
  Pcg32 rng(seed, 0);
  size_t kept = 0, cast = 0;
  for (size_t attempts = 0; kept < lines && attempts < 64 * lines; ++attempts) {
    // An isotropic direction, and an offset uniform on the disc of the bounding sphere perpendicular to it
    // (the same lines as the kd-tree's measurement for the same seed and root box).
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
    if (!intersect_slabs(root, line, nullptr, nullptr)) continue;
    ++kept;
    cross(data, line, 0, crossed);
    if (counter.prim_tests < max_ray_tests) {
      Hit hit;
      bvh.traverse(ray, &hit, false, counter);
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
