#include "raystep/accel/bsp.h"

#include "raystep/util/error.h"

namespace raystep {

void BspTree::build(const Geometry& geometry) {
  geometry_ = &geometry;
  tree_ = build_bsp(geometry, options_);
  // The traversal's stack holds one entry per level below the root: the tree may not be deeper.
  for (const BspNodeInfo& info : tree_.info)
    if (info.depth > kBspMaxDepth)
      throw InputError("", 0, "bsp: deeper than " + std::to_string(kBspMaxDepth));
  mailboxes_.reset(geometry.size());
}

}  // namespace raystep
