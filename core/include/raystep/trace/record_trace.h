// Recording rays through whichever structure records events (the grid, the kd-trees): the one entry point for
// the command line and the debugger, so that a new structure is added in one place.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

// True for structures whose traversal record_trace can log.
bool records_events(const Accelerator& accel);

// Throws InputError("", 0, ...) for a structure that records no events (brute, bvol).
Trace record_trace(const Geometry& geometry, const Accelerator& accel, const std::vector<RayRequest>& rays,
                   const std::string& scene_path, const std::string& scene_hash);

}  // namespace raystep
