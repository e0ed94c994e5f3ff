#include "raystep/trace/record_trace.h"

#include "raystep/trace/grid_trace.h"
#include "raystep/trace/kd_trace.h"
#include "raystep/util/error.h"

namespace raystep {

bool records_events(const Accelerator& accel) {
  return dynamic_cast<const UniformGrid*>(&accel) || dynamic_cast<const KdTree*>(&accel);
}

Trace record_trace(const Geometry& geometry, const Accelerator& accel, const std::vector<RayRequest>& rays,
                   const std::string& scene_path, const std::string& scene_hash) {
  if (auto* grid = dynamic_cast<const UniformGrid*>(&accel))
    return record_grid_trace(geometry, *grid, rays, scene_path, scene_hash);
  if (auto* kd = dynamic_cast<const KdTree*>(&accel))
    return record_kd_trace(geometry, *kd, rays, scene_path, scene_hash);
  throw InputError("", 0, "the " + accel.name() + " structure records no events (use grid, kd or kd-median)");
}

}  // namespace raystep
