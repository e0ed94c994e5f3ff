#include "raystep/accel/grid.h"

#include <algorithm>
#include <cmath>

#include "raystep/geometry/tri_box_overlap.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {
// Bounds on memory, so that no scene or option can make the build allocate without limit.
constexpr size_t kMaxCells = size_t(1) << 26;
constexpr size_t kMaxReferences = size_t(1) << 28;
}  // namespace

std::array<int, 3> UniformGrid::resolution_for(const Bounds3& bounds, size_t prim_count, float density) {
  // max(nx, ny, nz) = d * cbrt(n); the other axes in proportion to the box's extents, each at least 1.
  glm::vec3 e = bounds.extent();
  float max_extent = std::max({e.x, e.y, e.z});
  float n_max = std::max(1.f, std::round(density * std::cbrt(float(std::max<size_t>(prim_count, 1)))));
  std::array<int, 3> n;
  for (int a = 0; a < 3; ++a) {
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
    // The same expression as the 3D-DDA's boundaries, so that cells and walk agree.
    b.lo[a] = bounds_.lo[a] + float(c[a]) * cell_size_[a];
    b.hi[a] = c[a] + 1 == n_[a] ? bounds_.hi[a] : bounds_.lo[a] + float(c[a] + 1) * cell_size_[a];
  }
  return b;
}

void UniformGrid::build(const Geometry& geometry) {
  geometry_ = &geometry;
  cell_start_.clear();
  prim_index_.clear();
  occupied_.clear();
  mailboxes_.reset(geometry.size());
  if (geometry.size() == 0) return;

  // The scene's bounding box; a flat axis (a planar scene) gets a thickness so that cells have a size.
  bounds_ = geometry.bounds();
  glm::vec3 e = bounds_.extent();
  float max_extent = std::max({e.x, e.y, e.z});
  for (int a = 0; a < 3; ++a) {
    if (e[a] > max_extent * 1e-6f) continue;
    float magnitude = std::max(std::fabs(bounds_.lo[a]), std::fabs(bounds_.hi[a]));
    float pad = std::max({max_extent * 1e-3f, magnitude * 1e-5f, 1e-30f});
    bounds_.lo[a] -= pad;
    bounds_.hi[a] += pad;
  }

  std::array<int, 3> n = options_.resolution ? *options_.resolution
                                             : resolution_for(bounds_, geometry.size(), options_.density);
  for (int a = 0; a < 3; ++a)
    if (n[a] < 1 || n[a] > 4096) throw InputError("", 0, "grid resolution must be 1..4096 per axis");
  if (size_t(n[0]) * n[1] * n[2] > kMaxCells)
    throw InputError("", 0, "grid resolution " + std::to_string(n[0]) + "x" + std::to_string(n[1]) + "x" +
                                std::to_string(n[2]) + " has more than " + std::to_string(kMaxCells) + " cells");
  for (int a = 0; a < 3; ++a) {
    n_[a] = n[a];
    cell_size_[a] = (bounds_.hi[a] - bounds_.lo[a]) / float(n[a]);
    inv_cell_size_[a] = float(n[a]) / (bounds_.hi[a] - bounds_.lo[a]);
  }

  // Place each primitive in the cells it overlaps: candidates from its bounding box (widened by a relative
  // margin against rounding), then, with exact insertion, the separating axis test.
  struct Ref {
    uint32_t cell, prim;
  };
  std::vector<Ref> refs;
  refs.reserve(geometry.size() * 2);
  for (uint32_t id = 0; id < geometry.size(); ++id) {
    Bounds3 pb = geometry.prim_bounds(id);
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      double margin = 1.0 / (1 << 20);
      double x0 = (double(pb.lo[a]) - bounds_.lo[a]) * inv_cell_size_[a];
      double x1 = (double(pb.hi[a]) - bounds_.lo[a]) * inv_cell_size_[a];
      lo[a] = int(std::clamp(std::floor(x0 - margin * (1.0 + std::fabs(x0))), 0.0, double(n_[a] - 1)));
      hi[a] = int(std::clamp(std::floor(x1 + margin * (1.0 + std::fabs(x1))), 0.0, double(n_[a] - 1)));
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          if (options_.exact_insert) {
            Bounds3 cb = cell_bounds(i, j, k);
            bool overlap = geometry.type(id) == PrimType::triangle
                               ? triangle_overlaps_box(geometry.vertex(id, 0), geometry.vertex(id, 1),
                                                       geometry.vertex(id, 2), cb)
                               : sphere_overlaps_box(geometry.sphere(id).center, geometry.sphere(id).radius, cb);
            if (!overlap) continue;
          }
          if (refs.size() >= kMaxReferences)
            throw InputError("", 0, "grid: more than " + std::to_string(kMaxReferences) +
                                        " primitive references; use a lower resolution");
          refs.push_back({uint32_t(cell_id(i, j, k)), id});
        }
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

bool UniformGrid::intersect(const Ray& ray, Hit* hit) const {
  NullRecorder rec;
  return traverse(ray, hit, false, rec);
}

bool UniformGrid::occluded(const Ray& ray) const {
  NullRecorder rec;
  Hit hit;
  return traverse(ray, &hit, true, rec);
}

}  // namespace raystep
