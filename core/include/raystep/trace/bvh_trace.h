// Recording rays through a bounding volume hierarchy into a Trace (format version 3): each ray walked with
// the event recorder (node, box_test, push, pop, skip, leaf, prim_test, ...), plus every node its events name
// and the chain of parents of each up to the root (box, children or primitives), and the primitives they
// name, so the trace replays on its own.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/bvh.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

// The binary BVH (kinds "bvh", "bvh-sweep", "bvh-median"). Shadow rays are walked as any-hit queries, the
// others as nearest-hit queries.
Trace record_bvh_trace(const Geometry& geometry, const Bvh& bvh, const std::vector<RayRequest>& rays,
                       const std::string& scene_path, const std::string& scene_hash);

// The wide BVH (kinds "bvh4", "bvh8"), with its node ids as WideBvh::describe() numbers them (every child
// slot has one); its nodes have no split axis (TraceNode::axis -1).
Trace record_wide_bvh_trace(const Geometry& geometry, const WideBvh& bvh, const std::vector<RayRequest>& rays,
                            const std::string& scene_path, const std::string& scene_hash);

}  // namespace raystep
