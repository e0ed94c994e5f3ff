// A structure seen from above, as the slides draw it in 2D: the lines that cut the plane (a grid's cell
// boundaries, a kd-tree's split lines, an octree's centre lines, a BSP tree's planes as the chords they cut
// through their cells) and each node's region (a box, or a BSP cell's convex polygon), for a figure or a 2D
// view to draw and to highlight the node a walk is at. Projected on the plane z = 0 (x, y of 3D points).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "raystep/accel/accelerator.h"

namespace raystep {

struct OutlineLine {
  glm::vec2 a, b;
  int32_t node = -1;  // the node whose split it is (-1: a grid line)
  int32_t depth = 0;
};
struct OutlineRegion {
  int32_t node = -1;
  int32_t depth = 0;
  bool leaf = false;
  std::vector<glm::vec2> polygon;  // counter-clockwise; a box's four corners
  std::string path;  // from the root in the slides' notation (L below / first, R above / second;
                     // an octree a digit per level): "" the root, and every node of a wide BVH
                     // (its traces name no path)
};
struct PlaneOutline {
  std::string kind;            // the structure's name
  bool boxes = false;          // BVH: the regions are the (overlapping) node boxes, drawn as such; no lines
  glm::vec2 lo{0.f}, hi{0.f};  // the root's region
  std::vector<OutlineLine> lines;
  std::vector<OutlineRegion> regions;  // by node id where the structure has nodes (regions[i].node == i)
  // Grid: the resolution and the boundaries, for the cell of a trace's cell index.
  int grid[2] = {0, 0};
  size_t total_nodes = 0;  // nodes the structure has; regions holds at most max_nodes of them (depth first)
};

// True for the structures plane_outline draws: grid, kd, kd-median, octree, bsp, bvh, bvh-sweep, bvh-median,
// bvh4 and bvh8 (a wide BVH's nodes numbered as its traces number them, WideBvh::describe).
bool has_plane_outline(const Accelerator& accel);
// The built structure's outline, nodes of depth 0..d for the largest d with at most max_nodes of them (a
// grid's lines: every boundary). Throws InputError("", 0, ...) for a structure without one.
PlaneOutline plane_outline(const Accelerator& accel, size_t max_nodes = 100000);

}  // namespace raystep
