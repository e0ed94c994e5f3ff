// Recording rays through the uniform grid into a Trace: each ray walked with the event recorder, plus the
// boxes of the cells it visited and the primitives its events name, so the trace replays on its own.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/grid.h"
#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

// Shadow rays are walked as any-hit queries, the others as nearest-hit queries.
Trace record_grid_trace(const Geometry& geometry, const UniformGrid& grid, const std::vector<RayRequest>& rays,
                        const std::string& scene_path, const std::string& scene_hash);

}  // namespace raystep
