#include <algorithm>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bounding_volumes.h"
#include "raystep/accel/brute_force.h"
#include "raystep/accel/bsp.h"
#include "raystep/accel/bvh.h"
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
  return {"brute",     "bvol",       "grid", "kd",   "kd-median", "bvh",
          "bvh-sweep", "bvh-median", "bvh4", "bvh8", "octree",    "bsp"};
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
  if (name == "bvh" || name == "bvh-sweep" || name == "bvh-median") {
    BvhOptions bvh = options.bvh;
    bvh.builder = name == "bvh-sweep"    ? BvhBuilder::sweep
                  : name == "bvh-median" ? BvhBuilder::median
                                         : BvhBuilder::binned;
    return std::make_unique<Bvh>(bvh, options.bvh_order);
  }
  if (name == "octree") return std::make_unique<Octree>(options.octree);
  if (name == "bvh4" || name == "bvh8") return std::make_unique<WideBvh>(name == "bvh4" ? 4 : 8, options.bvh);
  if (name == "bsp") return std::make_unique<BspTree>(options.bsp, options.kd_mailboxes);
  std::string known;
  for (const std::string& n : accelerator_names()) known += (known.empty() ? "" : ", ") + n;
  for (size_t i = 1; i < bvol_kind_names().size(); ++i) known += ", " + bvol_kind_names()[i];
  throw InputError("", 0, "unknown accelerator '" + name + "' (known: " + known + ")");
}

}  // namespace raystep
