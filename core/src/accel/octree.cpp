#include "raystep/accel/octree.h"

namespace raystep {

void Octree::build(const Geometry& geometry) {
  geometry_ = &geometry;
  tree_ = build_octree(geometry, options_);
  stats_ = octree_stats(tree_);
  mailboxes_.reset(geometry.size());
}

}  // namespace raystep
