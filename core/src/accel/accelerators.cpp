// The accelerators by name (make_accelerator), and their build options as a cache key (structure_key).
#include <algorithm>
#include <cstdio>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bounding_volumes.h"
#include "raystep/accel/brute_force.h"
#include "raystep/accel/bsp.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/bvh_names.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/structure_options.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/util/error.h"

namespace raystep {

// ---- Brute force: every primitive, in id order ----

template <class Recorder>
static bool brute_walk(const Geometry& g, const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) {
  *hit = Hit{};
  rec.ray_begin(ray);
  if (SlabRay(ray).valid) {
    WatertightRay wray(ray);
    float t_max = ray.tmax;
    for (uint32_t id = 0; id < g.size(); ++id) {
      Hit candidate;
      bool found = g.intersect(id, ray, wray, t_max, &candidate);
      rec.prim_test(id, found, candidate.t);
      if (!found) continue;
      *hit = candidate;
      t_max = candidate.t;
      if (any_hit) break;
    }
  }
  rec.ray_end(*hit);
  return hit->found();
}

bool BruteForce::intersect(const Ray& ray, Hit* hit) const {
  NullRecorder rec;
  return brute_walk(*geometry_, ray, hit, false, rec);
}

bool BruteForce::occluded(const Ray& ray) const {
  NullRecorder rec;
  Hit hit;
  return brute_walk(*geometry_, ray, &hit, true, rec);
}

bool BruteForce::intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const {
  return brute_walk(*geometry_, ray, hit, false, counters);
}

bool BruteForce::occluded_counted(const Ray& ray, CountingRecorder& counters) const {
  Hit hit;
  return brute_walk(*geometry_, ray, &hit, true, counters);
}

// ---- Factory ----

std::vector<std::string> accelerator_names() {
  std::vector<std::string> names = {"brute", "bvol", "grid", "kd", "kd-median"};
  for (const std::string& n : bvh_names()) names.push_back(n);
  names.push_back("octree");
  names.push_back("bsp");
  return names;
}

std::string recorded_structure_list(bool trees_only) {
  std::vector<std::string> names = accelerator_names();
  names.erase(std::remove_if(names.begin(), names.end(),
                             [&](const std::string& n) {
                               return n == "brute" || n == "bvol" || (trees_only && n == "grid");
                             }),
              names.end());
  std::string out;
  for (size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return out;
}

std::unique_ptr<Accelerator> make_accelerator(const std::string& name) {
  return make_accelerator(name, StructureOptions{});
}

std::unique_ptr<Accelerator> make_accelerator(const std::string& name, const StructureOptions& options) {
  if (name == "brute") return std::make_unique<BruteForce>();
  if (std::optional<BvolKind> kind = parse_bvol_kind(name)) return std::make_unique<BoundingVolumes>(*kind);
  if (name == "grid") return std::make_unique<UniformGrid>(options.grid);
  if (name == "kd" || name == "kd-median") {
    KdOptions kd = options.kd;
    kd.builder = name == "kd-median" ? KdBuilder::median : KdBuilder::sah;
    return std::make_unique<KdTree>(kd, options.kd_mailboxes);
  }
  if (std::optional<BvhName> b = parse_bvh_name(name)) {
    BvhOptions bvh = options.bvh;
    bvh.builder = b->builder;
    if (b->width == 2) return std::make_unique<Bvh>(bvh, options.bvh_order);
    return std::make_unique<WideBvh>(b->width, bvh);
  }
  if (name == "octree") return std::make_unique<Octree>(options.octree);
  if (name == "bsp") return std::make_unique<BspTree>(options.bsp, options.kd_mailboxes);
  std::string known;
  for (const std::string& n : accelerator_names()) known += (known.empty() ? "" : ", ") + n;
  for (size_t i = 1; i < bvol_kind_names().size(); ++i) known += ", " + bvol_kind_names()[i];
  throw InputError("", 0, "unknown accelerator '" + name + "' (known: " + known + ")");
}

std::string structure_key(const std::string& accel, const StructureOptions& o) {
  char buf[384];
  const GridOptions& g = o.grid;
  const BvhOptions& b = o.bvh;
  std::snprintf(buf, sizeof buf, "%s|%.9g|%d,%d,%d|%d|%.9g|%.9g|%.9g|%d|%d|%.9g|%d|%.9g|%.9g|%d|%d|%d|%d|%d",
                accel.c_str(), double(g.density), g.resolution ? (*g.resolution)[0] : 0,
                g.resolution ? (*g.resolution)[1] : 0, g.resolution ? (*g.resolution)[2] : 0,
                int(g.exact_insert), double(o.kd.t_i), double(o.kd.t_t), double(o.kd.empty_bonus),
                o.kd.max_depth, o.kd.leaf_size, double(o.kd.reference_budget), int(o.kd_mailboxes),
                double(b.t_i), double(b.t_t), b.bins, b.leaf_size, b.max_leaf_size, b.max_depth,
                int(o.bvh_order));
  // The octree's and the BSP tree's own options (the BSP tree's costs and limits are the kd-tree's).
  char more[200];
  std::snprintf(more, sizeof more, "|%d|%d|%d|%d|%.9g|%.9g|%d|%d|%.9g|%.9g", o.octree.leaf_size,
                o.octree.max_depth, int(o.bsp.directions), o.bsp.candidates, double(o.bsp.t_i),
                double(o.bsp.t_t), o.bsp.max_depth, o.bsp.leaf_size, double(b.spatial_alpha),
                double(b.spatial_budget));
  return std::string(buf) + more;
}

}  // namespace raystep
