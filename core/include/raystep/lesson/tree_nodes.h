// The tree a lesson's `node`, `node-path` and `panel` settings name, for every structure that is a tree: the
// kd-trees, the BVHs, the general BSP tree and the octree. One place for the lesson runner and the debugger,
// so that a node path means the same in `raystep lesson check` and in the presenter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "raystep/accel/accelerator.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

struct LessonTree {
  const char* name = nullptr;  // "kd-tree", "BVH", "BSP tree", "octree"; null: the structure is no tree
  size_t nodes = 0;            // node ids are 0 .. nodes - 1, the ids trace events use
  bool paths = false;          // whether node-path can name its nodes (a wide BVH's cannot)
};
LessonTree lesson_tree(const Accelerator& accel);

// The node at the end of a path from the root: kd-tree and BSP tree, L below the plane and R above; binary
// BVH, L the first child and R the second; octree, one digit 0..7 per level, the child's octant (bit 0: the
// upper half in x, bit 1 in y, bit 2 in z). Throws InputError("", 0, "why") when the path leaves the tree,
// has a letter the tree does not take, or the structure takes no paths.
uint32_t lesson_node_by_path(const Accelerator& accel, const std::string& path);

}  // namespace raystep
