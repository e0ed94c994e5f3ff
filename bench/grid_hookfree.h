// A copy of UniformGrid::traverse with every recorder hook removed, for the benchmark that proves the
// null recorder costs nothing: the two must time the same (and count the same instructions under callgrind).
// Keep it in step with core/include/raystep/accel/grid.h.
#pragma once

#include "raystep/accel/grid.h"

namespace raystep::bench {

inline bool grid_intersect_hookfree(const UniformGrid& grid, const Ray& ray, Hit* hit) {
  *hit = Hit{};
  SlabRay slab(ray);
  float t_enter, t_exit;
  if (grid.empty() || !intersect_slabs(grid.bounds(), slab, &t_enter, &t_exit)) return false;
  std::array<int, 3> n = grid.resolution();
  glm::vec3 start = ray.at(t_enter);
  int cell[3], step[3], out[3];
  float t_max[3], inv_d[3];
  const float* positions[3] = {grid.boundaries(0), grid.boundaries(1), grid.boundaries(2)};
  const float origin[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  auto boundary_t = [&](int axis, int index) { return (positions[axis][index] - origin[axis]) * inv_d[axis]; };
  for (int a = 0; a < 3; ++a) {
    cell[a] = grid.cell_of(start[a], a);
    float d = ray.direction[a];
    inv_d[a] = 1.f / d;
    if (d > 0.f) {
      while (cell[a] > 0 && boundary_t(a, cell[a]) > t_enter) --cell[a];
      step[a] = 1;
      out[a] = n[size_t(a)];
      t_max[a] = boundary_t(a, cell[a] + 1);
    } else if (d < 0.f) {
      while (cell[a] + 1 < n[size_t(a)] && boundary_t(a, cell[a] + 1) > t_enter) ++cell[a];
      step[a] = -1;
      out[a] = -1;
      t_max[a] = boundary_t(a, cell[a]);
    } else {
      step[a] = 0;
      out[a] = -2;
      t_max[a] = kInfinity;
    }
  }
  const std::ptrdiff_t stride[3] = {1, std::ptrdiff_t(n[0]), std::ptrdiff_t(n[0]) * n[1]};
  const std::ptrdiff_t id_step[3] = {step[0] * stride[0], step[1] * stride[1], step[2] * stride[2]};
  size_t id = grid.cell_id(cell[0], cell[1], cell[2]);
  MailboxStamp mailbox = grid.mailboxes().begin_ray();
  WatertightRay wray(ray);
  const Geometry& geometry = grid.geometry();
  float t_nearest = ray.tmax, t_limit = ray.tmax;
  for (;;) {
    int axis = (t_max[0] <= t_max[1] && t_max[0] <= t_max[2]) ? 0 : (t_max[1] <= t_max[2] ? 1 : 2);
    float t_cell_exit = std::min(t_max[axis], t_exit);
    uint32_t first = 0, last = 0;
    if (grid.occupied(id)) first = grid.cell_start(id), last = grid.cell_start(id + 1);
    for (uint32_t r = first; r < last; ++r) {
      uint32_t prim = grid.reference(r);
      if (!mailbox.first_visit(prim)) continue;
      Hit candidate;
      if (!geometry.intersect(prim, ray, wray, t_limit, &candidate)) continue;
      if (candidate.t == t_nearest && int32_t(prim) > hit->prim) continue;
      *hit = candidate;
      t_nearest = candidate.t;
      t_limit = next_float_up(t_nearest);
    }
    if (hit->found() && t_nearest * (1.f + 1.f / 4096.f) < t_cell_exit) break;
    if (t_max[axis] > t_exit + std::fabs(t_exit) * (1.f / 4096.f)) break;
    cell[axis] += step[axis];
    if (cell[axis] == out[axis]) break;
    id += size_t(id_step[axis]);
    t_max[axis] = boundary_t(axis, cell[axis] + (step[axis] > 0));
  }
  return hit->found();
}

}  // namespace raystep::bench
