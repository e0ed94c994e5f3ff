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

void KdTree::prepare_leaves() {
  leaf_triangles_.clear();
  if (!geometry_->all_triangles()) return;
  leaf_triangles_.resize(tree_.prim_index.size());
  for (size_t i = 0; i < tree_.prim_index.size(); ++i) {
    const uint32_t prim = tree_.prim_index[i];
    leaf_triangles_[i] = {geometry_->vertex(prim, 0), geometry_->vertex(prim, 1), geometry_->vertex(prim, 2), prim};
  }
}

void KdTree::build(const Geometry& geometry) {
  geometry_ = &geometry;
  tree_ = build_kdtree(geometry, options_);
  check_depth(tree_);
  mailboxes_.reset(geometry.size());
  prepare_leaves();
}

void KdTree::build(const Geometry& geometry, BuildListener& listener) {
  geometry_ = &geometry;
  tree_ = build_kdtree(geometry, options_, listener);
  check_depth(tree_);
  mailboxes_.reset(geometry.size());
  prepare_leaves();
}

bool KdTree::intersect(const Ray& ray, Hit* hit) const {
  NullRecorder rec;
  return traverse(ray, hit, false, rec);
}

bool KdTree::occluded(const Ray& ray) const {
  NullRecorder rec;
  Hit hit;
  return traverse(ray, &hit, true, rec);
}

}  // namespace raystep
