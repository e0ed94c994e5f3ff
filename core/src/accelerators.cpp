#include <algorithm>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bounding_volumes.h"
#include "raystep/accel/brute_force.h"
#include "raystep/accel/grid.h"
#include "raystep/util/error.h"

namespace raystep {

// ---- Brute force ----

bool BruteForce::intersect(const Ray& ray, Hit* hit) const {
  *hit = Hit{};
  if (!SlabRay(ray).valid) return false;
  WatertightRay wray(ray);
  float t_max = ray.tmax;
  for (uint32_t id = 0; id < geometry_->size(); ++id)
    if (geometry_->intersect(id, ray, wray, t_max, hit)) t_max = hit->t;
  return hit->found();
}

bool BruteForce::occluded(const Ray& ray) const {
  if (!SlabRay(ray).valid) return false;
  WatertightRay wray(ray);
  Hit hit;
  for (uint32_t id = 0; id < geometry_->size(); ++id)
    if (geometry_->intersect(id, ray, wray, ray.tmax, &hit)) return true;
  return false;
}

// ---- Bounding volumes ----

void BoundingVolumes::build(const Geometry& geometry) {
  geometry_ = &geometry;
  boxes_.clear();
  for (const Object& o : geometry.objects()) boxes_.push_back(o.bounds);
}

bool BoundingVolumes::intersect(const Ray& ray, Hit* hit) const {
  *hit = Hit{};
  SlabRay slab(ray);
  if (!slab.valid) return false;
  // Enter the boxes the ray crosses, nearest first.
  struct Entry {
    float t_enter;
    uint32_t object;
  };
  thread_local std::vector<Entry> entered;  // reused: no allocation per ray
  entered.clear();
  for (uint32_t o = 0; o < boxes_.size(); ++o) {
    float t0, t1;
    if (intersect_slabs(boxes_[o], slab, &t0, &t1)) entered.push_back({t0, o});
  }
  std::sort(entered.begin(), entered.end(), [](const Entry& a, const Entry& b) { return a.t_enter < b.t_enter; });
  WatertightRay wray(ray);
  float t_max = ray.tmax;
  for (const Entry& e : entered) {
    if (e.t_enter > t_max) break;  // every remaining box starts beyond the nearest hit
    const Object& obj = geometry_->objects()[e.object];
    for (uint32_t id = obj.first_prim; id < obj.first_prim + obj.prim_count; ++id)
      if (geometry_->intersect(id, ray, wray, t_max, hit)) t_max = hit->t;
  }
  return hit->found();
}

bool BoundingVolumes::occluded(const Ray& ray) const {
  SlabRay slab(ray);
  if (!slab.valid) return false;
  WatertightRay wray(ray);
  Hit hit;
  for (uint32_t o = 0; o < boxes_.size(); ++o) {
    if (!intersect_slabs(boxes_[o], slab, nullptr, nullptr)) continue;
    const Object& obj = geometry_->objects()[o];
    for (uint32_t id = obj.first_prim; id < obj.first_prim + obj.prim_count; ++id)
      if (geometry_->intersect(id, ray, wray, ray.tmax, &hit)) return true;
  }
  return false;
}

// ---- Factory ----

std::vector<std::string> accelerator_names() { return {"brute", "bvol", "grid"}; }

std::unique_ptr<Accelerator> make_accelerator(const std::string& name) {
  if (name == "brute") return std::make_unique<BruteForce>();
  if (name == "bvol") return std::make_unique<BoundingVolumes>();
  if (name == "grid") return std::make_unique<UniformGrid>();
  std::string known;
  for (const std::string& n : accelerator_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("", 0, "unknown accelerator '" + name + "' (known: " + known + ")");
}

}  // namespace raystep
