// Recording rays through the general BSP tree into a Trace (kind "bsp", version 4): each ray walked with the
// event recorder (the kd-tree's node, push, pop, leaf, prim_test and hit events), plus every node its events
// name with its plane (normal and offset) or primitives, and the bounding box of its convex cell.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/bsp.h"
#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

// Shadow rays are walked as any-hit queries, the others as nearest-hit queries.
Trace record_bsp_trace(const Geometry& geometry, const BspTree& tree, const std::vector<RayRequest>& rays,
                       const std::string& scene_path, const std::string& scene_hash);

}  // namespace raystep
