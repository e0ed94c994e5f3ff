// Recording rays through whichever structure records events (the grid, the kd-trees, the BVHs): the one entry
// point for the command line and the debugger, so that a new structure is added in one place.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

// True for structures whose traversal record_trace can log.
bool records_events(const Accelerator& accel);

// Throws InputError("", 0, ...) for a structure that records no events (brute, bvol).
Trace record_trace(const Geometry& geometry, const Accelerator& accel, const std::vector<RayRequest>& rays,
                   const std::string& scene_path, const std::string& scene_hash);

// An anti-aliased pixel's trace (version 2), for `raystep trace --pixel X,Y --aa SPEC` and the debugger
// alike: pixel (px, py) of a width x height image sampled as render_image samples it with this seed (its
// samples, adaptive squares and value in Trace::pixel), and every sample's primary ray, with secondary also
// its shadow, reflected and refracted rays, recorded through the structure with TracedRay::sample set.
// TracePixel::exact is left empty: a caller that knows the exact value fills it.
// Throws InputError("", 0, ...) for a pixel outside the image, settings out of range or not expressible as an
// anti-aliasing spec (the trace names the pattern by its spec), or a structure that records no events.
Trace record_pixel_trace(const Scene& scene, const Accelerator& accel, int width, int height, int px, int py,
                         const AntiAliasing& aa, uint64_t seed, bool secondary, const std::string& scene_path,
                         const std::string& scene_hash);

}  // namespace raystep
