// Uniform grid (lecture: "Uniform grids"): the scene's bounding box cut into nx x ny x nz cells with
// max(nx, ny, nz) = d * cbrt(n), each primitive stored in every cell it really overlaps (exact SAT test) or,
// as an option, every cell its bounding box overlaps. Traversal is the 3D-DDA of Amanatides and Woo
// ("A Fast Voxel Traversal Algorithm", 1987) with incremental arithmetic and per-thread mailboxes, walking
// until the next cell's entry exceeds the nearest hit: "traverse until tmin(cell) > tmax(ray)". Memory is
// bounded: the density rule's resolution is coarsened when the scene would need more references than a
// budget.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/mailbox.h"
#include "raystep/accel/nearest_hit.h"
#include "raystep/accel/recorded_walk.h"
#include "raystep/geometry/bounds.h"
#include "raystep/geometry/component.h"
#include "raystep/record/recorder.h"

namespace raystep {

struct GridOptions {
  float density = 3.f;                           // d in max(nx, ny, nz) = d * cbrt(n)
  std::optional<std::array<int, 3>> resolution;  // explicit nx, ny, nz (overrides density)
  bool exact_insert = true;                      // false: insert by bounding box
};

// Why a grid's resolution differs from the one asked for.
enum class GridCoarsening {
  none,
  reference_budget,  // the density rule's resolution would exceed UniformGrid::reference_budget
};
const char* to_string(GridCoarsening c);

class UniformGrid final : public RecordedWalk<UniformGrid, GridOptions> {
 public:
  explicit UniformGrid(GridOptions options = {}) : RecordedWalk(options) {}
  std::string name() const override { return "grid"; }
  void build(const Geometry& geometry) override;
  size_t memory_bytes() const override {
    return cell_start_.capacity() * sizeof(uint32_t) + prim_index_.capacity() * sizeof(uint32_t) +
           occupied_.capacity() * sizeof(uint64_t) +
           (boundaries_[0].capacity() + boundaries_[1].capacity() + boundaries_[2].capacity()) *
               sizeof(float);
  }

  // The traversal kernel, instrumented through the recorder (see record/recorder.h).
  template <class Recorder>
  bool traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const;

  // The lecture's resolution rule, exposed for tests and lessons: in space max(nx, ny, nz) = d * cbrt(n), in
  // the plane max(nx, ny) = d * sqrt(n) with nz = 1.
  static std::array<int, 3> resolution_for(const Bounds3& bounds, size_t prim_count, float density,
                                           SplitSpace space = {});

  // Bounded memory and build time on any scene: a build stores at most reference_budget(n) =
  // min(2^28, max(2^22, 32 n)) primitive references. It first counts, allocating nothing, each primitive's
  // bounding-box cells: the references under bbox insertion; under exact insertion the triangle-box tests,
  // held to 4 budgets. Exact insertion then stops as soon as its references pass the budget. Either way, the
  // density rule's resolution is coarsened (all axes alike) until the build fits, and coarsened() says so; an
  // explicit resolution is refused (InputError) instead, since who names the cells wants those cells.
  static size_t reference_budget(size_t prim_count);

  const Bounds3& bounds() const { return bounds_; }
  std::array<int, 3> resolution() const { return {n_[0], n_[1], n_[2]}; }
  // The resolution asked for (explicit, or the density rule's) and why the built one differs, if it does.
  std::array<int, 3> requested_resolution() const { return requested_; }
  GridCoarsening coarsening() const { return coarsening_; }
  bool coarsened() const { return coarsening_ != GridCoarsening::none; }
  glm::vec3 cell_size() const { return cell_size_; }
  Bounds3 cell_bounds(int i, int j, int k) const;
  size_t reference_count() const { return prim_index_.size(); }
  // Primitive ids stored in cell (i, j, k).
  const uint32_t* cell_begin(int i, int j, int k) const {
    return &prim_index_[cell_start_[cell_id(i, j, k)]];
  }
  const uint32_t* cell_end(int i, int j, int k) const {
    return &prim_index_[0] + cell_start_[cell_id(i, j, k) + 1];
  }
  const Mailboxes& mailboxes() const { return mailboxes_; }
  // The position of cell boundary `index` (0..n) on an axis: lo + index * size, and hi at n. cell_bounds()
  // gives the cells the primitives are inserted in by these positions, and the 3D-DDA crosses these very
  // boundaries (it reads the same table), so walk and cells agree to the last bit.
  float boundary(int axis, int index) const { return boundaries_[axis][size_t(index)]; }
  const float* boundaries(int axis) const { return boundaries_[axis].data(); }  // the n + 1 of an axis
  // The cell index containing coordinate p on an axis, clamped to the grid (NaN gives 0).
  int cell_of(float p, int axis) const {
    float x = (p - component(bounds_.lo, axis)) * component(inv_cell_size_, axis);
    if (!(x >= 0.f)) return 0;  // also NaN
    if (x >= float(n_[axis])) return n_[axis] - 1;
    return int(x);
  }
  size_t cell_id(int i, int j, int k) const { return (size_t(k) * n_[1] + j) * n_[0] + i; }
  uint32_t cell_start(size_t id) const { return cell_start_[id]; }
  uint32_t reference(uint32_t r) const { return prim_index_[r]; }
  bool empty() const { return cell_start_.empty(); }
  // One bit per cell: does it hold any primitive? The walk reads these bits (a few hundred KiB that stay in
  // cache) and touches the offsets only for occupied cells, so empty space costs little even in a fine grid.
  bool occupied(size_t id) const { return (occupied_[id >> 6] >> (id & 63)) & 1u; }

 private:
  // Set n_ and the cell size for resolution n.
  void set_resolution(const std::array<int, 3>& n);
  // The sum over primitives of their candidate cells at the current resolution (allocates nothing).
  size_t count_box_cells() const;
  // A primitive's candidate cells: those its bounding box (widened against rounding) overlaps.
  void box_cells(uint32_t id, int lo[3], int hi[3]) const;

  Bounds3 bounds_;
  int n_[3] = {1, 1, 1};
  std::array<int, 3> requested_{1, 1, 1};
  GridCoarsening coarsening_ = GridCoarsening::none;
  glm::vec3 cell_size_{1.f}, inv_cell_size_{1.f};
  std::vector<float> boundaries_[3];  // per axis, the n + 1 boundary positions (boundary())
  std::vector<uint32_t> cell_start_;  // nx*ny*nz + 1 offsets into prim_index_ (compact storage)
  std::vector<uint32_t> prim_index_;
  std::vector<uint64_t> occupied_;  // one bit per cell: cell_start_[id] < cell_start_[id + 1]
  Mailboxes mailboxes_;
};

template <class Recorder>
bool UniformGrid::traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
  *hit = Hit{};
  rec.ray_begin(ray);
  // Enter the grid by the slab test; the walk covers [t_enter, t_exit] of the ray.
  SlabRay slab(ray);
  float t_enter, t_exit;
  if (cell_start_.empty() || !intersect_slabs(bounds_, slab, &t_enter, &t_exit)) {
    rec.ray_end(*hit);
    return false;
  }

  // Set up the 3D-DDA: the start cell (clamped), and per axis stepX and tMaxX (t of the next boundary).
  // tDeltaX, a cell's width in t, is shown to the recorder only: the walk computes each boundary's t from its
  // position.
  glm::vec3 start = ray.at(t_enter);
  int cell[3], step[3], out[3];
  float t_max[3];  // plain arrays: indexed by a run-time axis without glm's switch
  float inv_d[3];  // 1 / d: a boundary's t is (position - origin) * inv_d, with no division
  // The boundary positions and the ray's origin as plain arrays too, for boundary_t in the loop.
  const float* positions[3] = {boundaries_[0].data(), boundaries_[1].data(), boundaries_[2].data()};
  const float origin[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  // The t where the ray meets boundary `index` (0..n) of an axis.
  auto boundary_t = [&](int axis, int index) {
    return (positions[axis][index] - origin[axis]) * inv_d[axis];
  };
  for (int a = 0; a < 3; ++a) {
    cell[a] = cell_of(start[a], a);
    float d = ray.direction[a];
    inv_d[a] = 1.f / d;
    // The start point is rounded (by half an ulp of its coordinates, a good part of a cell far from the
    // world's origin): where it landed beyond a boundary that the ray crosses after t_enter, the walk starts
    // a cell earlier, so that no cell of the ray's path is skipped. (One that landed short costs an empty
    // step.)
    if (d > 0.f) {  // +0 and -0 both fall through to "never step on this axis"
      while (cell[a] > 0 && boundary_t(a, cell[a]) > t_enter) --cell[a];
      step[a] = 1;
      out[a] = n_[a];
      t_max[a] = boundary_t(a, cell[a] + 1);
    } else if (d < 0.f) {
      while (cell[a] + 1 < n_[a] && boundary_t(a, cell[a] + 1) > t_enter) ++cell[a];
      step[a] = -1;
      out[a] = -1;
      t_max[a] = boundary_t(a, cell[a]);
    } else {
      step[a] = 0;
      out[a] = -2;  // never reached
      t_max[a] = kInfinity;
    }
  }

  // The cell's index in the arrays, stepped like the cell itself: one addition per step.
  const std::ptrdiff_t stride[3] = {1, std::ptrdiff_t(n_[0]), std::ptrdiff_t(n_[0]) * n_[1]};
  const std::ptrdiff_t id_step[3] = {step[0] * stride[0], step[1] * stride[1], step[2] * stride[2]};
  size_t id = cell_id(cell[0], cell[1], cell[2]);

  MailboxStamp mailbox = mailboxes_.begin_ray();
  WatertightRay wray(ray);
  NearestHit nearest(ray.tmax);
  float t_cell_enter = t_enter;
  for (;;) {
    // The axis whose boundary comes first is stepped next; ties go to the lowest axis (x, then y, then z),
    // so a ray through an edge or a vertex visits the cells around it one axis at a time.
    int axis = (t_max[0] <= t_max[1] && t_max[0] <= t_max[2]) ? 0 : (t_max[1] <= t_max[2] ? 1 : 2);
    float t_cell_exit = std::min(t_max[axis], t_exit);
    if constexpr (Recorder::enabled) {
      glm::vec3 t_delta(kInfinity);
      for (int a = 0; a < 3; ++a)
        if (step[a] != 0) t_delta[a] = cell_size_[a] / std::fabs(ray.direction[a]);
      rec.cell(GridCellStep{cell[0], cell[1], cell[2], t_cell_enter, t_cell_exit,
                            glm::vec3(t_max[0], t_max[1], t_max[2]), t_delta,
                            t_max[axis] <= t_exit ? axis : -1});
    } else
      rec.cell(GridCellStep{});

    // Test the cell's primitives, skipping those already tested for this ray (mailbox).
    uint32_t first = 0, last = 0;  // an empty cell's offsets are never read
    if (occupied(id)) first = cell_start_[id], last = cell_start_[id + 1];
    for (uint32_t r = first; r < last; ++r) {
      uint32_t prim = prim_index_[r];
      if (!nearest.test(*geometry_, prim, ray, wray, &mailbox, rec)) continue;
      if (any_hit) {
        rec.hit_accepted(prim, nearest.t, AcceptReason::any_hit);
        *hit = nearest.hit;
        rec.ray_end(*hit);
        return true;
      }
      // A hit beyond this cell's exit may yet be beaten by a primitive of a later cell: keep it, go on.
      if (nearest.t * (1.f + 1.f / 4096.f) >= t_cell_exit) rec.hit_deferred(prim, nearest.t, t_cell_exit);
    }

    // Traverse until tmin(next cell) > tmax(ray): the next cell starts at this cell's exit. A computed t can
    // stray a few ulps (slivers: ~1e-5 relative) past the exact plane distance, so a hit within a relative
    // 2^-12 of the exit is left to the next cell, where a primitive hit just beyond the boundary is tested
    // too.
    if (nearest.found() && nearest.t * (1.f + 1.f / 4096.f) < t_cell_exit) {
      rec.hit_accepted(uint32_t(nearest.hit.prim), nearest.t, AcceptReason::inside_cell);
      break;
    }
    // The ray leaves the grid (or its interval ends) in this cell. A computed tMax strays from the exact
    // boundary distance by a few ulps (the rounded reciprocal; summed step by step it strayed by many): a
    // boundary computed within the same relative 2^-12 beyond the exit may truly lie before it (a ray leaving
    // the grid through a cell edge at a mesh vertex), and that cell is visited too (cells past the grid's
    // last one are not: `out` below).
    if (t_max[axis] > t_exit + std::fabs(t_exit) * (1.f / 4096.f)) {
      if (nearest.found())
        rec.hit_accepted(uint32_t(nearest.hit.prim), nearest.t, AcceptReason::structure_done);
      break;
    }
    // Step to the neighbour along that axis. tMax is not advanced by tDelta: the sum drifts from the
    // boundaries the primitives were inserted by (each addition rounds at the magnitude of t, which is large
    // for a far origin, and a cell far from the world's origin is only a few ulps of its coordinates wide),
    // and a ray that left a cell early by that drift skipped the diagonal neighbour holding its hit. So the
    // next boundary's t is computed from its position, as the first one was: tMax + tDelta up to rounding.
    cell[axis] += step[axis];
    if (cell[axis] == out[axis]) {
      if (nearest.found())
        rec.hit_accepted(uint32_t(nearest.hit.prim), nearest.t, AcceptReason::structure_done);
      break;
    }
    id += size_t(id_step[axis]);
    t_cell_enter = t_max[axis];
    t_max[axis] = boundary_t(axis, cell[axis] + (step[axis] > 0));
  }
  *hit = nearest.hit;
  rec.ray_end(*hit);
  return hit->found();
}

}  // namespace raystep
