#include "raystep/accel/grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "raystep/geometry/tri_box_overlap.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {
// Bounds on memory, so that no scene or option can make the build allocate without limit.
constexpr size_t kMaxCells = size_t(1) << 26;
constexpr size_t kMaxReferences = size_t(1) << 28;
// The reference budget: references per primitive, and a floor so that small scenes keep fine grids (2^22
// references are 48 MiB while building).
constexpr size_t kBudgetPerPrimitive = 32;
constexpr size_t kBudgetFloor = size_t(1) << 22;
// Exact insertion tests candidate cells that the primitive may miss: up to this many tests per reference in
// the budget (long diagonal triangles miss most of their boxes' cells), so the build time is bounded too.
constexpr size_t kTestsPerReference = 4;

std::string resolution_text(const std::array<int, 3>& n) {
  return std::to_string(n[0]) + "x" + std::to_string(n[1]) + "x" + std::to_string(n[2]);
}
}  // namespace

const char* to_string(GridCoarsening c) {
  switch (c) {
    case GridCoarsening::none:
      return "none";
    case GridCoarsening::reference_budget:
      return "reference budget";
  }
  return "?";
}

size_t UniformGrid::reference_budget(size_t prim_count) {
  return std::min(kMaxReferences, std::max(kBudgetFloor, kBudgetPerPrimitive * prim_count));
}

std::array<int, 3> UniformGrid::resolution_for(const Bounds3& bounds, size_t prim_count, float density,
                                               SplitSpace space) {
  // max(nx, ny, nz) = d * cbrt(n); the other axes in proportion to the box's extents, each at least 1. In the
  // plane max(nx, ny) = d * sqrt(n) and nz = 1: n objects in d^2 n cells, as n in d^3 n cells in space.
  glm::vec3 e = bounds.extent();
  if (space.plane()) e.z = 0.f;
  float max_extent = std::max({e.x, e.y, e.z});
  const float count = float(std::max<size_t>(prim_count, 1));
  float n_max = std::max(1.f, std::round(density * (space.plane() ? std::sqrt(count) : std::cbrt(count))));
  std::array<int, 3> n = {1, 1, 1};
  for (int a = 0; a < space.axes; ++a) {
    float share = max_extent > 0.f ? e[a] / max_extent : 1.f;
    n[a] = int(std::clamp(std::round(n_max * share), 1.f, 4096.f));
  }
  // Keep the cell count bounded: shrink all axes alike.
  while (size_t(n[0]) * n[1] * n[2] > kMaxCells)
    for (int& v : n) v = std::max(1, v * 3 / 4);
  return n;
}

Bounds3 UniformGrid::cell_bounds(int i, int j, int k) const {
  int c[3] = {i, j, k};
  Bounds3 b;
  for (int a = 0; a < 3; ++a) {
    // The 3D-DDA's boundaries, so that cells and walk agree.
    b.lo[a] = boundary(a, c[a]);
    b.hi[a] = boundary(a, c[a] + 1);
  }
  return b;
}

void UniformGrid::set_resolution(const std::array<int, 3>& n) {
  for (int a = 0; a < 3; ++a) {
    n_[a] = n[a];
    cell_size_[a] = (bounds_.hi[a] - bounds_.lo[a]) / float(n[a]);
    inv_cell_size_[a] = float(n[a]) / (bounds_.hi[a] - bounds_.lo[a]);
    boundaries_[a].resize(size_t(n[a]) + 1);
    for (int i = 0; i < n[a]; ++i) boundaries_[a][size_t(i)] = bounds_.lo[a] + float(i) * cell_size_[a];
    boundaries_[a][size_t(n[a])] = bounds_.hi[a];
  }
}

void UniformGrid::box_cells(uint32_t id, int lo[3], int hi[3]) const {
  // The bounding box widened by a relative margin, so that rounding never loses a cell the primitive touches.
  Bounds3 pb = geometry_->prim_bounds(id);
  for (int a = 0; a < 3; ++a) {
    double margin = 1.0 / (1 << 20);
    double x0 = (double(pb.lo[a]) - bounds_.lo[a]) * inv_cell_size_[a];
    double x1 = (double(pb.hi[a]) - bounds_.lo[a]) * inv_cell_size_[a];
    lo[a] = int(std::clamp(std::floor(x0 - margin * (1.0 + std::fabs(x0))), 0.0, double(n_[a] - 1)));
    hi[a] = int(std::clamp(std::floor(x1 + margin * (1.0 + std::fabs(x1))), 0.0, double(n_[a] - 1)));
  }
}

size_t UniformGrid::count_box_cells() const {
  size_t count = 0;  // at most 2^32 primitives of 2^26 cells each: no overflow
  for (uint32_t id = 0; id < geometry_->size(); ++id) {
    int lo[3], hi[3];
    box_cells(id, lo, hi);
    count += size_t(hi[0] - lo[0] + 1) * size_t(hi[1] - lo[1] + 1) * size_t(hi[2] - lo[2] + 1);
  }
  return count;
}

void UniformGrid::build(const Geometry& geometry) {
  geometry_ = &geometry;
  cell_start_.clear();
  prim_index_.clear();
  occupied_.clear();
  coarsening_ = GridCoarsening::none;
  mailboxes_.reset(geometry.size());
  if (geometry.size() == 0) {
    set_resolution({n_[0], n_[1], n_[2]});  // boundary() stays defined
    return;
  }

  // The scene's bounding box; a flat axis (a planar scene) gets a thickness so that cells have a size.
  bounds_ = geometry.bounds();
  glm::vec3 e = bounds_.extent();
  float max_extent = std::max({e.x, e.y, e.z});
  // Coordinates near the float range (the OBJ reader accepts up to 3.4e38) can span more than it: cells of
  // infinite size. Refused by name (the resolution rule below would divide infinities).
  if (!std::isfinite(max_extent))
    throw InputError(
        "", 0, "grid: the scene's extent overflows single precision (its coordinates span more than 3.4e38)");
  for (int a = 0; a < 3; ++a) {
    if (e[a] > max_extent * 1e-6f) continue;
    float magnitude = std::max(std::fabs(bounds_.lo[a]), std::fabs(bounds_.hi[a]));
    float pad = std::max({max_extent * 1e-3f, magnitude * 1e-5f, 1e-30f});
    bounds_.lo[a] -= pad;
    bounds_.hi[a] += pad;
  }

  std::array<int, 3> n = options_.resolution ? *options_.resolution
                                             : resolution_for(bounds_, geometry.size(), options_.density,
                                                              geometry.split_space());
  for (int a = 0; a < 3; ++a)
    if (n[a] < 1 || n[a] > 4096) throw InputError("", 0, "grid resolution must be 1..4096 per axis");
  if (size_t(n[0]) * n[1] * n[2] > kMaxCells)
    throw InputError(
        "", 0,
        "grid resolution " + resolution_text(n) + " has more than " + std::to_string(kMaxCells) + " cells");
  requested_ = n;
  set_resolution(n);

  // Reference budget. Coarsening shrinks all axes alike by the factor that would fit if the count fell with
  // the cube of the resolution, its square in the plane (it falls no faster, so one step never overshoots),
  // at least 5%; an explicit resolution is refused instead.
  const size_t budget = reference_budget(geometry.size());
  if (geometry.size() > budget)
    throw InputError("", 0, "grid: more than " + std::to_string(budget) + " primitives");
  auto coarsen = [&](size_t count, size_t limit, const char* verb, const char* what) {
    if (options_.resolution)
      throw InputError("", 0,
                       "grid resolution " + resolution_text(n) + " " + verb + " " + std::to_string(count) +
                           " " + what + ", more than the budget of " + std::to_string(limit) + " for " +
                           std::to_string(geometry.size()) +
                           " primitives; ask for fewer cells, or let the density rule choose (it coarsens "
                           "to fit)");
    const double ratio = double(limit) / double(count);
    double scale = std::min(0.95, geometry.split_space().plane() ? std::sqrt(ratio) : std::cbrt(ratio));
    for (int& v : n) v = std::max(1, int(double(v) * scale));
    set_resolution(n);
    coarsening_ = GridCoarsening::reference_budget;
  };

  // Step 1, bounded work, nothing allocated: the candidate cells (bounding-box cells, O(n) to count) are the
  // references under bbox insertion and the triangle-box tests under exact insertion, which may test up to
  // kTestsPerReference candidates for each reference it may store.
  const bool exact = options_.exact_insert;
  const size_t candidate_limit = exact ? kTestsPerReference * budget : budget;
  size_t candidates = count_box_cells();
  for (; candidates > candidate_limit; candidates = count_box_cells())
    coarsen(candidates, candidate_limit, exact ? "would test" : "would store",
            exact ? "candidate cells (bounding-box cells)" : "references");

  // Step 2: place each primitive in the cells it overlaps: candidates from its bounding box, then, with exact
  // insertion, the separating axis test. Bounded memory: the insertion stops as soon as the references pass
  // the budget, and the grid is coarsened by the references extrapolated to all primitives (step 1's count
  // bounds this under bbox insertion, so it never stops).
  struct Ref {
    uint32_t cell, prim;
  };
  std::vector<Ref> refs;
  refs.reserve(std::min(candidates, budget + 1));
  for (;;) {
    refs.clear();
    uint32_t id = 0;
    for (; id < geometry.size() && refs.size() <= budget; ++id) {
      int lo[3], hi[3];
      box_cells(id, lo, hi);
      // One reference past the budget says enough (reserved: no reallocation).
      for (int k = lo[2]; k <= hi[2] && refs.size() <= budget; ++k)
        for (int j = lo[1]; j <= hi[1] && refs.size() <= budget; ++j)
          for (int i = lo[0]; i <= hi[0] && refs.size() <= budget; ++i) {
            if (exact) {
              Bounds3 cb = cell_bounds(i, j, k);
              bool overlap =
                  geometry.type(id) == PrimType::triangle
                      ? triangle_overlaps_box(geometry.vertex(id, 0), geometry.vertex(id, 1),
                                              geometry.vertex(id, 2), cb)
                      : sphere_overlaps_box(geometry.sphere(id).center, geometry.sphere(id).radius, cb);
              if (!overlap) continue;
            }
            refs.push_back({uint32_t(cell_id(i, j, k)), id});
          }
    }
    if (refs.size() <= budget) break;
    size_t estimate = size_t(double(refs.size()) * double(geometry.size()) / double(id));
    coarsen(std::max(estimate, budget + 1), budget, "would store about", "references");
  }

  // Compact storage: counting sort of the references by cell (primitive order kept within a cell).
  size_t cells = size_t(n_[0]) * n_[1] * n_[2];
  cell_start_.assign(cells + 1, 0);
  for (const Ref& r : refs) ++cell_start_[r.cell + 1];
  for (size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  prim_index_.resize(refs.size());
  std::vector<uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (const Ref& r : refs) prim_index_[fill[r.cell]++] = r.prim;
  occupied_.assign((cells + 63) / 64, 0u);
  for (size_t c = 0; c < cells; ++c)
    if (cell_start_[c] < cell_start_[c + 1]) occupied_[c >> 6] |= uint64_t(1) << (c & 63);
}

}  // namespace raystep
