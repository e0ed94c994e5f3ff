// Shared by the structures' trace recorders (grid_trace.cpp, kd_trace.cpp, bvh_trace.cpp, ...): the scene and
// structure every trace starts with, walk each requested ray with the event recorder, and collect the
// primitives and tree nodes the events name.
#pragma once

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "raystep/record/event_recorder.h"
#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"

namespace raystep::detail {

// A trace of the scene at scene_path, about to record rays through the structure named kind.
inline Trace begin_trace(const Geometry& geometry, const std::string& kind, const std::string& scene_path,
                         const std::string& scene_hash) {
  Trace t;
  t.scene_path = scene_path;
  t.scene_hash = scene_hash;
  t.scene_primitives = geometry.size();
  t.structure.kind = kind;
  return t;
}

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

// The same for a structure whose kernel is traverse(ray, hit, any_hit, recorder): shadow rays ask for any
// hit.
template <class Structure>
void record_traversals(const Geometry& geometry, const std::vector<RayRequest>& rays,
                       const Structure& structure, Trace* trace) {
  record_rays(
      geometry, rays,
      [&](const RayRequest& req, EventRecorder& rec) {
        Hit hit;
        structure.traverse(req.ray, &hit, req.kind == RayKind::shadow, rec);
      },
      trace);
}

// The tree nodes the events of every ray name: nodes visited, pushed, popped, skipped, and both ends of a box
// test (a kd-tree's walk emits no box tests or skips).
inline std::set<int32_t> named_nodes(const Trace& t) {
  std::set<int32_t> named;
  for (const TracedRay& tr : t.rays) {
    for (const Event& e : tr.events) {
      switch (e.type) {
        case EventType::box_test:
          if (e.parent >= 0) named.insert(e.parent);
          [[fallthrough]];
        case EventType::node:
        case EventType::push:
        case EventType::pop:
        case EventType::leaf:
        case EventType::skip:
          named.insert(e.node);
          break;
        default:
          break;
      }
    }
  }
  return named;
}

// The named nodes and their parents up to the root, in id order: parent(id) gives -1 at the root.
template <class Parent>
std::set<int32_t> with_parent_chains(std::set<int32_t> ids, Parent parent) {
  std::vector<int32_t> todo(ids.begin(), ids.end());
  while (!todo.empty()) {
    int32_t p = parent(todo.back());
    todo.pop_back();
    if (p >= 0 && ids.insert(p).second) todo.push_back(p);
  }
  return ids;
}

// A tree node as traces give it: its place in the tree and box, and a leaf's primitives (count of them from
// prim_index[first]); the caller adds what its kind of inner node has (split, plane, children).
inline TraceNode trace_node(int32_t id, int32_t parent, int depth, const Bounds3& box, bool leaf,
                            const std::vector<uint32_t>& prim_index, uint32_t first, uint32_t count) {
  TraceNode tn;
  tn.id = id;
  tn.parent = parent;
  tn.depth = depth;
  tn.box = box;
  tn.leaf = leaf;
  if (leaf)
    for (uint32_t i = 0; i < count; ++i) tn.prims.push_back(int32_t(prim_index[first + i]));
  return tn;
}

// A structure's parameter as traces give it, a number or a text ("builder": "sah").
inline void add_param(TraceStructure* s, const char* key, double number) {
  s->params.push_back({key, false, number, ""});
}
inline void add_text_param(TraceStructure* s, const char* key, std::string text) {
  s->params.push_back({key, true, 0.0, std::move(text)});
}

inline void sort_params(TraceStructure* s) {
  std::sort(s->params.begin(), s->params.end(),
            [](const TraceParam& a, const TraceParam& b) { return a.key < b.key; });
}

}  // namespace raystep::detail
