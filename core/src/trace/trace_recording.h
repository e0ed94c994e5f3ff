// Shared by the structures' trace recorders (grid_trace.cpp, kd_trace.cpp): walk each requested ray with the
// event recorder, and collect the primitives the events name.
#pragma once

#include <algorithm>
#include <set>
#include <vector>

#include "raystep/trace/event_recorder.h"
#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"

namespace raystep::detail {

// walk(request, recorder) traverses one ray. Fills trace->rays and trace->primitives.
template <class Walk>
void record_rays(const Geometry& geometry, const std::vector<RayRequest>& rays, Walk walk, Trace* trace) {
  std::set<int32_t> prims;
  EventRecorder rec;
  for (const RayRequest& req : rays) {
    rec.clear();
    walk(req, rec);
    TracedRay tr;
    tr.ray = req.ray;
    tr.kind = req.kind;
    tr.depth = req.depth;
    tr.has_pixel = req.has_pixel;
    tr.pixel[0] = req.pixel[0];
    tr.pixel[1] = req.pixel[1];
    tr.sample = req.sample;
    tr.events = rec.events();
    for (const Event& e : tr.events)
      if (e.prim >= 0) prims.insert(e.prim);
    trace->rays.push_back(std::move(tr));
  }
  for (int32_t id : prims) {
    TracePrimitive p;
    p.id = id;
    p.type = geometry.type(uint32_t(id));
    if (p.type == PrimType::triangle) {
      for (int k = 0; k < 3; ++k) p.v[k] = geometry.vertex(uint32_t(id), k);
    } else {
      p.v[0] = geometry.sphere(uint32_t(id)).center;
      p.radius = geometry.sphere(uint32_t(id)).radius;
    }
    trace->primitives.push_back(p);
  }
}

inline void sort_params(TraceStructure* s) {
  std::sort(s->params.begin(), s->params.end(),
            [](const TraceParam& a, const TraceParam& b) { return a.key < b.key; });
}

}  // namespace raystep::detail
