// Recording rays through the uniform grid into a Trace: each ray walked with the event recorder, plus the
// boxes of the cells it visited and the primitives its events name, so the trace replays on its own.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/grid.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

// A ray to record, with what the tracer knows of it.
struct RayRequest {
  Ray ray;
  RayKind kind = RayKind::primary;
  int depth = 0;
  bool has_pixel = false;
  int pixel[2] = {0, 0};
};

// Shadow rays are walked as any-hit queries, the others as nearest-hit queries.
Trace record_grid_trace(const Geometry& geometry, const UniformGrid& grid, const std::vector<RayRequest>& rays,
                        const std::string& scene_path, const std::string& scene_hash);

}  // namespace raystep
