#include "raystep/accel/octree.h"

namespace raystep {

void Octree::build(const Geometry& geometry) {
  geometry_ = &geometry;
  tree_ = build_octree(geometry, options_);
  mailboxes_.reset(geometry.size());
}

bool Octree::intersect(const Ray& ray, Hit* hit) const {
  NullRecorder rec;
  return traverse(ray, hit, false, rec);
}

bool Octree::occluded(const Ray& ray) const {
  NullRecorder rec;
  Hit hit;
  return traverse(ray, &hit, true, rec);
}

}  // namespace raystep
