// Recording rays through the kd-tree into a Trace: each ray walked with the event recorder, plus every node
// its events name (box, split plane or primitives) and the primitives they name, so the trace replays alone.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/kdtree.h"
#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

// Shadow rays are walked as any-hit queries, the others as nearest-hit queries.
Trace record_kd_trace(const Geometry& geometry, const KdTree& tree, const std::vector<RayRequest>& rays,
                      const std::string& scene_path, const std::string& scene_hash);

}  // namespace raystep
