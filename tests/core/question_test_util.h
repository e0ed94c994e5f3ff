// What the quiz tests (question_test.cpp, question_trees_test.cpp) share: the soup's fixed random rays, and
// the nearest hit among a walk's first events as the kernels keep it.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"

namespace raystep::test {

// 200 random rays from a sphere of radius 4 (outside the soup's box [-2, 2]^3) through a random point inside
// it, fixed seed.
inline std::vector<RayRequest> soup_rays(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<RayRequest> rays;
  while (rays.size() < 200) {
    glm::vec3 o(u(rng), u(rng), u(rng));
    if (glm::length(o) < 1e-3f) continue;
    o = 4.f * o / glm::length(o);
    const glm::vec3 target = 1.8f * glm::vec3(u(rng), u(rng), u(rng));
    RayRequest r;
    r.ray.origin = o;
    r.ray.direction = glm::normalize(target - o);
    rays.push_back(r);
  }
  return rays;
}

// The nearest hit among the prim_test events before `end`, ties to the lower id (as the kernels keep it).
inline void nearest_before(const std::vector<Event>& ev, size_t end, int32_t* prim, float* t) {
  *prim = -1;
  for (size_t i = 0; i < end; ++i) {
    const Event& e = ev[i];
    if (e.type != EventType::prim_test || !e.hit) continue;
    if (*prim >= 0 && (e.t > *t || (e.t == *t && e.prim > *prim))) continue;
    *prim = e.prim;
    *t = e.t;
  }
}

}  // namespace raystep::test
