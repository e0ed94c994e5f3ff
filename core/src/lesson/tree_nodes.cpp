// Trees by kind for the lesson layer (tree_nodes.h): the node counts and the paths of each tree.
#include "raystep/lesson/tree_nodes.h"

#include "raystep/accel/bsp.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, what);
}

// core's path functions name the command line's option ("--path 'LRL': ..."): the reason alone.
std::string reason_of(const InputError& e) {
  std::string why = e.detail();
  if (size_t colon = why.find("': "); why.rfind("--path", 0) == 0 && colon != std::string::npos)
    why = why.substr(colon + 3);
  return why;
}

}  // namespace

LessonTree lesson_tree(const Accelerator& accel) {
  if (auto* kd = dynamic_cast<const KdTree*>(&accel)) return {"kd-tree", kd->data().nodes.size(), true};
  if (auto* bvh = dynamic_cast<const Bvh*>(&accel)) return {"BVH", bvh->data().nodes.size(), true};
  if (auto* wide = dynamic_cast<const WideBvh*>(&accel)) return {"BVH", wide->describe().nodes.size(), false};
  if (auto* bsp = dynamic_cast<const BspTree*>(&accel)) return {"BSP tree", bsp->data().nodes.size(), true};
  if (auto* oct = dynamic_cast<const Octree*>(&accel)) return {"octree", oct->data().nodes.size(), true};
  return {};
}

uint32_t lesson_node_by_path(const Accelerator& accel, const std::string& path) {
  try {
    if (auto* kd = dynamic_cast<const KdTree*>(&accel)) return kd_node_by_path(kd->data(), path);
    if (auto* bvh = dynamic_cast<const Bvh*>(&accel)) return bvh_node_by_path(bvh->data(), path);
  } catch (const InputError& e) {
    fail(reason_of(e));
  }
  if (auto* bsp = dynamic_cast<const BspTree*>(&accel)) {
    // Depth-first preorder as the kd-tree: the child below the plane follows its parent.
    const std::vector<BspNode>& nodes = bsp->data().nodes;
    if (nodes.empty()) fail("the BSP tree is empty");
    uint32_t id = 0;
    for (size_t i = 0; i < path.size(); ++i) {
      if (path[i] != 'L' && path[i] != 'R') fail("use L (below the plane) and R (above) for a BSP tree");
      if (nodes[id].is_leaf())
        fail("node " + std::to_string(id) + " (after '" + path.substr(0, i) + "') is a leaf");
      id = path[i] == 'L' ? id + 1 : nodes[id].above_child();
    }
    return id;
  }
  if (auto* oct = dynamic_cast<const Octree*>(&accel)) {
    const std::vector<OctreeNode>& nodes = oct->data().nodes;
    if (nodes.empty()) fail("the octree is empty");
    const bool quad = oct->data().axes == 2;
    uint32_t id = 0;
    for (size_t i = 0; i < path.size(); ++i) {
      if (path[i] < '0' || path[i] > (quad ? '3' : '7'))
        fail(quad ? "use one digit 0..3 per level for a 2D scene's quadtree (the child's quadrant: 1 upper x, "
                    "2 upper y)"
                  : "use one digit 0..7 per level for an octree (the child's octant: 1 upper x, 2 upper y, 4 "
                    "upper z)");
      if (nodes[id].is_leaf())
        fail("cell " + std::to_string(id) + " (after '" + path.substr(0, i) + "') is a leaf");
      id = nodes[id].child(path[i] - '0');
    }
    return id;
  }
  fail("a path names a node of a kd-tree, binary BVH, BSP tree or octree");
}

}  // namespace raystep
