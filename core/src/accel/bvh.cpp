#include "raystep/accel/bvh.h"

namespace raystep {

std::string Bvh::name() const {
  switch (options_.builder) {
    case BvhBuilder::sweep:
      return "bvh-sweep";
    case BvhBuilder::median:
      return "bvh-median";
    case BvhBuilder::binned:
    default:
      return "bvh";
  }
}

void Bvh::build(const Geometry& geometry) {
  geometry_ = &geometry;
  bvh_ = build_bvh(geometry, options_);
}

void Bvh::build(const Geometry& geometry, BvhBuildListener& listener) {
  geometry_ = &geometry;
  bvh_ = build_bvh(geometry, options_, listener);
}

bool Bvh::intersect(const Ray& ray, Hit* hit) const {
  NullRecorder rec;
  return traverse(ray, hit, false, rec);
}

bool Bvh::occluded(const Ray& ray) const {
  NullRecorder rec;
  Hit hit;
  return traverse(ray, &hit, true, rec);
}

bool Bvh::intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const {
  return traverse(ray, hit, false, counters);
}

bool Bvh::occluded_counted(const Ray& ray, CountingRecorder& counters) const {
  Hit hit;
  return traverse(ray, &hit, true, counters);
}

size_t Bvh::memory_bytes() const {
  return bvh_.nodes.capacity() * sizeof(BvhNode) + bvh_.info.capacity() * sizeof(BvhNodeInfo) +
         bvh_.prim_index.capacity() * sizeof(uint32_t);
}

}  // namespace raystep
