// The octree's child order at the current inner cell, for the replay (Revelles, Ureña, Lastra 2000: the
// entry plane picks the first child, each exit plane the next).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raystep/replay/replay_state.h"

namespace raystep::replay {

// Octree (Revelles, Ureña, Lastra 2000): the order of the current inner cell's children along the ray. The
// entry plane (the cell face the ray enters by: the largest of the three entry t's) picks the first child:
// on the entry axis the near half, on the others the half the ray is in at t_enter (their centre planes
// crossed before it or not). Each next child is the neighbour across the plane the ray leaves the child by
// (the smallest of its three exit t's); a cell face instead of a centre plane: the ray leaves the parent.
struct OctreeChildStep {
  int octant = 0;     // 0..7: bit 0 upper half in x, bit 1 y, bit 2 z (the trace's children order); 0..3 in a quadtree
  int32_t node = -1;  // its id (from the trace's children list; -1 unknown)
  int exit_axis = 0;  // the plane it is left by
  float t_exit = 0.f;
  bool leaves_parent = false;  // that plane is the parent's face
};
struct OctreeChoice {
  bool valid = false;  // false: the current node is not an inner octree cell, or the trace has not its cell
  int axes = 3;        // 2: a 2D scene's quadtree (four children, cut on x and y)
  int node_event = -1;
  int32_t node = -1;
  int depth = 0;
  float t_enter = 0.f, t_exit = 0.f;  // the cell's part of the ray
  int entry_axis = -1;  // -1: the ray starts inside the cell (then t_enter is the ray's own start)
  float t0[3] = {0, 0, 0}, t1[3] = {0, 0, 0}, t_mid[3] = {0, 0, 0};  // per axis: entry, exit, centre plane
  bool moving[3] = {true, true, true};                               // false: the direction's component is 0
  std::vector<OctreeChildStep> path;  // by the planes, as the lecture's algorithm walks them
  std::vector<int32_t> visited;       // the children the events visit under this cell, in order
  std::vector<int> visited_octants;   // their octants (-1: not found among the children)
  int visited_so_far = 0;             // how many of them are at or before the current event
};
bool is_octree_ray(const Trace* trace, const TracedRay& ray);
// The current octree cell's child order (the node event of s.node_event, or the push right after it).
OctreeChoice octree_choice(const Trace& trace, const TracedRay& ray, const ReplayState& s);
// "x+ y- z+": an octant's halves (+ upper, - lower); a quadtree's quadrant (axes 2): "x+ y-".
std::string octant_name(int octant, int axes = 3);

}  // namespace raystep::replay
