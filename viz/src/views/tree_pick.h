// What a click in the 3D view selects in a tree (lecture: "which cell holds this point?"): the leaf of the
// kd-tree, binary or wide BVH, octree or general BSP tree that holds the picked point of the picked
// primitive, found by going down the tree as a point location would (by the split plane, the octant, the
// general plane's side; a BVH by the primitive, which sits in one leaf, or after spatial splits in
// several: the one whose box holds the point).
#pragma once

#include <glm/vec3.hpp>

namespace raystep::viz {

struct StructureData;

// p: the picked point on the surface of primitive prim (-1: unknown). Descends by p's side of each plane;
// where p lies within a hair of a plane (a picked point is rounded; scene-relative, 1e-5 of the root's
// diagonal) both sides are tried, and the first leaf reached that lists prim wins, else the first leaf
// reached. A BVH's boxes overlap, so its answer is the one leaf listing prim (without prim: the smallest leaf
// box holding p). -1: no tree, or p outside the root.
int leafAtPick(const StructureData& s, const glm::vec3& p, int prim);

}  // namespace raystep::viz
