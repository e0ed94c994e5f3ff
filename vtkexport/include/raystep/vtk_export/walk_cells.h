// One recorded ray's walk (lecture: "traversal": the cells or nodes a ray visits, front to back) for
// ParaView: the ray as a polyline from its origin to its hit, or to where it leaves the structure, and every
// event that names a cell or node (grid cell; tree node, leaf, push, pop; BVH box test, skip) as that cell or
// node's box with its position in the walk (step, seq), event type and interval [t_enter, t_exit]. Read from
// a Trace only, so that a trace file exports without the scene's structure being rebuilt.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/trace/trace_file.h"
#include "raystep/vtk_export/cell_set.h"

namespace raystep::vtk_export {

struct RayPath {
  std::vector<glm::vec3>
      points;            // the origin (at max(tmin, 0)), the entry into the structure if later, the end
  std::vector<float> t;  // the ray parameter of each point
  bool hit = false;
  int32_t prim = -1;  // the primitive hit (-1: a miss)
};

// A primitive test of the walk (a prim_test, or a mailbox_hit: a test the mailbox saved), with the
// primitive's shape as the trace carries it.
struct PrimitiveTest {
  TracePrimitive shape;
  uint32_t seq = 0;
  EventType type = EventType::prim_test;
  bool hit = false;
  float t = 0.f;  // prim_test with a hit: where
};

struct RayWalk {
  RayPath path;
  CellSet visited;                   // one cell per event naming a cell or node, in event order
  std::vector<PrimitiveTest> tests;  // in event order
};

// Throws InputError(trace_name, 0, ...) if an event names a cell, node or primitive the trace does not carry.
RayWalk ray_walk(const Trace& trace, size_t ray, const std::string& trace_name);

}  // namespace raystep::vtk_export
