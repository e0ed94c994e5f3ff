#include "raystep/trace/record_trace.h"

#include "raystep/scene/antialiasing_spec.h"
#include "raystep/trace/bsp_trace.h"
#include "raystep/trace/bvh_trace.h"
#include "raystep/trace/grid_trace.h"
#include "raystep/trace/kd_trace.h"
#include "raystep/trace/octree_trace.h"
#include "raystep/trace/pixel_rays.h"
#include "raystep/util/error.h"

namespace raystep {


bool records_events(const Accelerator& accel) {
  return dynamic_cast<const UniformGrid*>(&accel) || dynamic_cast<const KdTree*>(&accel) ||
         dynamic_cast<const Bvh*>(&accel) || dynamic_cast<const WideBvh*>(&accel) ||
         dynamic_cast<const Octree*>(&accel) || dynamic_cast<const BspTree*>(&accel);
}

Trace record_trace(const Geometry& geometry, const Accelerator& accel, const std::vector<RayRequest>& rays,
                   const std::string& scene_path, const std::string& scene_hash) {
  if (auto* grid = dynamic_cast<const UniformGrid*>(&accel))
    return record_grid_trace(geometry, *grid, rays, scene_path, scene_hash);
  if (auto* kd = dynamic_cast<const KdTree*>(&accel))
    return record_kd_trace(geometry, *kd, rays, scene_path, scene_hash);
  if (auto* bvh = dynamic_cast<const Bvh*>(&accel))
    return record_bvh_trace(geometry, *bvh, rays, scene_path, scene_hash);
  if (auto* wide = dynamic_cast<const WideBvh*>(&accel))
    return record_wide_bvh_trace(geometry, *wide, rays, scene_path, scene_hash);
  if (auto* octree = dynamic_cast<const Octree*>(&accel))
    return record_octree_trace(geometry, *octree, rays, scene_path, scene_hash);
  if (auto* bsp = dynamic_cast<const BspTree*>(&accel))
    return record_bsp_trace(geometry, *bsp, rays, scene_path, scene_hash);
  throw InputError("", 0, "the " + accel.name() + " structure records no events (use " + recorded_structure_list() + ")");
}

Trace record_pixel_trace(const Scene& scene, const Accelerator& accel, int width, int height, int px, int py,
                         const AntiAliasing& aa, uint64_t seed, bool secondary, const std::string& scene_path,
                         const std::string& scene_hash) {
  if (!records_events(accel))
    throw InputError("", 0, "the " + accel.name() + " structure records no events (use " + recorded_structure_list() + ")");
  if (width <= 0 || height <= 0 || px < 0 || py < 0 || px >= width || py >= height)
    throw InputError("", 0,
                     "pixel " + std::to_string(px) + "," + std::to_string(py) + " is outside the " +
                         std::to_string(width) + "x" + std::to_string(height) + " image");
  validate(aa);
  // The trace names the pattern by its spec: settings the spec cannot say (a threshold of 0, depth 0) would
  // make a file that no reader accepts.
  const std::string spec = to_string(aa);
  const AntiAliasing back = parse_antialiasing(spec);
  const bool adaptive = aa.mode == AntiAliasing::Mode::adaptive;
  const bool uses_k = !adaptive && aa.mode != AntiAliasing::Mode::none;
  if (back.mode != aa.mode || (uses_k && back.k != aa.k) ||
      (adaptive && (back.threshold != aa.threshold || back.max_depth != aa.max_depth)))
    throw InputError("", 0, "anti-aliasing " + spec + " cannot be recorded in a trace");

  PixelSampleRays sampled = pixel_sample_rays(scene, accel, width, height, px, py, aa, seed, secondary);
  Trace t = record_trace(scene.geometry, accel, sampled.rays, scene_path, scene_hash);
  TracePixel pixel;
  pixel.sampling = std::move(sampled.sampling);
  pixel.sampling.aa =
      back;  // as a reader reads it back (the fields the pattern does not use as the spec sets them)
  pixel.width = width;
  pixel.height = height;
  pixel.seed = seed;
  t.pixel = std::move(pixel);
  return t;
}

}  // namespace raystep
