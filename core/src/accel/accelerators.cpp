#include <algorithm>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bounding_volumes.h"
#include "raystep/accel/brute_force.h"
#include "raystep/accel/bsp.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
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

// ---- Bounding volumes: objects whose boxes the ray enters, nearest box first ----

void BoundingVolumes::build(const Geometry& geometry) {
  geometry_ = &geometry;
  boxes_.clear();
  for (const Object& o : geometry.objects()) boxes_.push_back(o.bounds);
}

template <class Recorder>
bool BoundingVolumes::walk(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
  *hit = Hit{};
  rec.ray_begin(ray);
  SlabRay slab(ray);
  if (!slab.valid) {
    rec.ray_end(*hit);
    return false;
  }
  // The boxes the ray crosses, by entry distance (a reused per-thread list: no allocation per ray).
  thread_local std::vector<std::pair<float, uint32_t>> entered;
  entered.clear();
  for (uint32_t o = 0; o < boxes_.size(); ++o) {
    float t0, t1;
    if (intersect_slabs(boxes_[o], slab, &t0, &t1)) entered.emplace_back(t0, o);
  }
  std::sort(entered.begin(), entered.end());
  WatertightRay wray(ray);
  float t_max = ray.tmax;
  for (const auto& [t_enter, o] : entered) {
    if (t_enter > t_max) break;  // every remaining box starts beyond the nearest hit
    rec.box_entered(o, t_enter);
    const Object& obj = geometry_->objects()[o];
    for (uint32_t id = obj.first_prim; id < obj.first_prim + obj.prim_count; ++id) {
      Hit candidate;
      bool found = geometry_->intersect(id, ray, wray, t_max, &candidate);
      rec.prim_test(id, found, candidate.t);
      if (!found) continue;
      *hit = candidate;
      t_max = candidate.t;
      if (any_hit) {
        rec.ray_end(*hit);
        return true;
      }
    }
  }
  rec.ray_end(*hit);
  return hit->found();
}

bool BoundingVolumes::intersect(const Ray& ray, Hit* hit) const {
  NullRecorder rec;
  return walk(ray, hit, false, rec);
}

bool BoundingVolumes::occluded(const Ray& ray) const {
  NullRecorder rec;
  Hit hit;
  return walk(ray, &hit, true, rec);
}

bool BoundingVolumes::intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const {
  return walk(ray, hit, false, counters);
}

bool BoundingVolumes::occluded_counted(const Ray& ray, CountingRecorder& counters) const {
  Hit hit;
  return walk(ray, &hit, true, counters);
}

// ---- Factory ----

std::vector<std::string> accelerator_names() {
  return {"brute",     "bvol",       "grid", "kd",   "kd-median", "bvh",
          "bvh-sweep", "bvh-median", "bvh4", "bvh8", "bsp"};
}

std::unique_ptr<Accelerator> make_accelerator(const std::string& name) {
  return make_accelerator(name, StructureOptions{});
}

std::unique_ptr<Accelerator> make_accelerator(const std::string& name, const StructureOptions& options) {
  if (name == "brute") return std::make_unique<BruteForce>();
  if (name == "bvol") return std::make_unique<BoundingVolumes>();
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
  if (name == "bvh4" || name == "bvh8") return std::make_unique<WideBvh>(name == "bvh4" ? 4 : 8, options.bvh);
  if (name == "bsp") return std::make_unique<BspTree>(options.bsp, options.kd_mailboxes);
  std::string known;
  for (const std::string& n : accelerator_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("", 0, "unknown accelerator '" + name + "' (known: " + known + ")");
}

}  // namespace raystep
