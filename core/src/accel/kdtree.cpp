#include "raystep/accel/kdtree.h"

#include "raystep/util/error.h"

namespace raystep {

namespace {
// The traversal's stack holds one entry per level below the root: the tree may not be deeper.
void check_depth(const KdTreeData& tree) {
  for (const KdNodeInfo& info : tree.info)
    if (info.depth > kKdMaxDepth) throw InputError("", 0, "kd-tree: deeper than " + std::to_string(kKdMaxDepth));
}
}  // namespace

void KdTree::build(const Geometry& geometry) {
  geometry_ = &geometry;
  tree_ = build_kdtree(geometry, options_);
  check_depth(tree_);
  mailboxes_.reset(geometry.size());
}

void KdTree::build(const Geometry& geometry, BuildListener& listener) {
  geometry_ = &geometry;
  tree_ = build_kdtree(geometry, options_, listener);
  check_depth(tree_);
  mailboxes_.reset(geometry.size());
}

}  // namespace raystep
