#include <algorithm>
#include <utility>
#include <vector>

#include "raystep/accel/bounding_volumes.h"

namespace raystep {

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

}  // namespace raystep
