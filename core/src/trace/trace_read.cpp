// Reading traces: the validating reader of versions 1 to 5 (the multi-walk form's walks through the same
// code), from a text or streamed from a file, every error naming the file, the line and the JSON path.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <unordered_map>
#include <unordered_set>

#include <nlohmann/json.hpp>

#include "raystep/scene/json_locate.h"
#include "raystep/util/memory_limit.h"
#include "trace_file_detail.h"
#include "trace_reader.h"

namespace raystep {

using nlohmann::json;
using namespace detail;

namespace {

// The document's JSON (the events streamed to `events`), or an InputError saying where it is malformed or that
// it is truncated. From the text when there is one, else from the file (then the text is read again only to
// find an error's line).
JsonTape parse_tape(const TraceText& source, std::FILE* file, const std::string& name, EventStreams* events) {
  try {
    return file ? JsonTape::parse_file(file, events) : JsonTape::parse(source.text(), events);
  } catch (const std::length_error& e) {
    throw InputError(name, 0, std::string("too large to read: ") + e.what());
  } catch (const std::bad_alloc&) {
    throw InputError(name, 0, "not enough memory to read it");
  } catch (const json::parse_error& e) {
    bool truncated = e.byte >= source.size();
    int line = json_line_at_byte(source.text(), e.byte);
    throw InputError(name, line,
                     truncated ? "the trace is truncated (unexpected end of the file)"
                               : std::string("malformed JSON: ") + e.what());
  } catch (const json::out_of_range& e) {
    // "number overflow parsing '1e400'" comes without a position: the line of that literal.
    std::string what = e.what();
    size_t q = what.find('\'');
    std::string literal = q == std::string::npos ? "" : what.substr(q + 1, what.rfind('\'') - q - 1);
    throw InputError(name, json_line_of_number(source.text(), literal), "malformed JSON: " + what);
  } catch (const json::exception& e) {
    throw InputError(name, 0, std::string("malformed JSON: ") + e.what());
  }
}

// Everything of a trace below its scene: the build events, structure, pixel, rays and geometry, read from doc
// (the document itself, or one walk of a multi-walk document at base) with the rules of this version.
void read_walk(const Reader& rd, const Value& doc, const Path& root, const Path* base, int64_t version,
               Trace& t, Capped capped, EventStreams& streams) {
  const Value st = rd.member(doc, root, "structure");
  const Path sp = sub(base, "structure");
  t.structure.kind = rd.text_at(st, sp, "kind");
  t.structure.bounds.lo = rd.vec_at(st, sp, "bounds_min");
  t.structure.bounds.hi = rd.vec_at(st, sp, "bounds_max");
  bool grid = t.structure.kind == "grid";
  if (grid) {
    const Value res = rd.array_at(st, sp, "resolution");
    const Path rp = sp.key("resolution");
    if (res.size() != 3) rd.fail(rp, "expected [nx, ny, nz]");
    for (int a = 0; a < 3; ++a) t.structure.resolution[a] = int(rd.integer(res[a], rp.at(a), 1, 4096));
  }
  for (const auto& [key, value] : st.members()) {
    if (key == "kind" || key == "bounds_min" || key == "bounds_max" || key == "resolution") continue;
    TraceParam p;
    p.key = std::string(key);
    if (value.is_string()) {
      p.is_text = true;
      p.text = std::string(value.get_string());
    } else {
      p.number = rd.real(value, sp.key(key));
    }
    t.structure.params.push_back(p);
  }

  // Version 3's bounding volume hierarchies: "bvh", "bvh-sweep", "bvh-median", "bvh4", "bvh8"; and the
  // octree (version 3 too), whose inner nodes list their eight children the same way.
  const bool octree = version >= 3 && t.structure.kind == "octree";
  size_t octree_children = 0;  // 8, or a 2D scene's quadtree's 4: the same for every inner cell
  const bool lists_children = (version >= 3 && t.structure.kind.rfind("bvh", 0) == 0) || octree;
  // Version 4's general BSP tree: every inner node has a plane.
  const bool bsp = version >= 4 && t.structure.kind == "bsp";
  const int64_t max_prim = int64_t(t.scene_primitives) - 1;
  int64_t max_node = INT32_MAX;  // trees: ids below the structure's node count, when it gives one
  for (const TraceParam& p : t.structure.params)
    if (p.key == "nodes" && !p.is_text) max_node = std::min<int64_t>(int64_t(p.number) - 1, INT32_MAX);
  const EventLimits limits{version, grid, t.structure.resolution, max_node, max_prim};

  // Version 2: an anti-aliased pixel's samples (version 1 had no such key: a reader ignores keys it does not
  // know).
  if (version >= 2 && doc.contains("pixel"))
    t.pixel = read_pixel(rd, doc.find("pixel"), sub(base, "pixel"), capped);

  const Value rays = rd.array_at(doc, root, "rays");
  t.rays.reserve(capped(rays.size()));
  const Path rays_path = sub(base, "rays");
  for (size_t r = 0; r < rays.size(); ++r) {
    const Path rp = rays_path.at(r);
    const Value jr = rays[r];
    TracedRay tr;
    tr.ray.origin = rd.vec_at(jr, rp, "origin");
    tr.ray.direction = rd.vec_at(jr, rp, "direction");
    tr.ray.tmin = rd.real_at(jr, rp, "tmin");
    tr.ray.tmax = rd.real_at(jr, rp, "tmax");
    std::string_view kind = rd.view_at(jr, rp, "kind");
    int k = name_index(kind, kRayKinds);
    if (k < 0) rd.fail(rp.key("kind"), "unknown ray kind \"" + std::string(kind) + "\"");
    tr.kind = RayKind(k);
    tr.depth = int(rd.integer_at(jr, rp, "depth", 0, 1000));
    if (jr.contains("pixel")) {
      const Value px = jr.find("pixel");
      const Path pp = rp.key("pixel");
      if (!px.is_array() || px.size() != 2) rd.fail(pp, "expected [x, y]");
      tr.has_pixel = true;
      tr.pixel[0] = int(rd.integer(px[0], pp.at(0), 0, 1 << 20));
      tr.pixel[1] = int(rd.integer(px[1], pp.at(1), 0, 1 << 20));
    }
    if (version >= 2 && jr.contains("sample")) {
      if (!t.pixel) rd.fail(rp.key("sample"), "a ray's sample needs the trace's \"pixel\" section");
      tr.sample = int(rd.integer_at(jr, rp, "sample", 0, int64_t(t.pixel->sampling.samples.size()) - 1));
    }
    const Value events = rd.array_at(jr, rp, "events");
    const Path events_path = rp.key("events");
    if (events.is_streamed()) {  // read as it was parsed: now its numbers against this walk's rules
      tr.events = streams.take(events.stream_number());
      check_events(rd, tr.events, events_path, limits);
    } else {
      tr.events.reserve(capped(events.size()));
      for (size_t i = 0; i < events.size(); ++i) tr.events.push_back(read_event(rd, events[i], events_path.at(i), i, limits));
    }
    if (tr.events.empty() || tr.events.front().type != EventType::ray_begin ||
        tr.events.back().type != EventType::ray_end)
      rd.fail(events_path, "a ray's events start with ray_begin and end with ray_end");
    t.rays.push_back(std::move(tr));
  }

  const Value geo = rd.member(doc, root, "geometry");
  const Path gp = sub(base, "geometry");
  const Value cells = rd.array_at(geo, gp, "cells");
  const Path cells_path = gp.key("cells");
  t.cells.reserve(capped(cells.size()));
  for (size_t i = 0; i < cells.size(); ++i) {
    const Path cp = cells_path.at(i);
    TraceCell c;
    const Value idx = rd.array_at(cells[i], cp, "cell");
    const Path ip = cp.key("cell");
    if (idx.size() != 3) rd.fail(ip, "expected [i, j, k]");
    for (int a = 0; a < 3; ++a)
      c.cell[a] = int(rd.integer(idx[a], ip.at(a), 0, grid ? t.structure.resolution[a] - 1 : (1 << 20)));
    c.box.lo = rd.vec_at(cells[i], cp, "min");
    c.box.hi = rd.vec_at(cells[i], cp, "max");
    t.cells.push_back(c);
  }
  // Tree nodes: ids below the structure's node count, each listed once, every node an event names listed.
  std::unordered_set<int32_t> listed;
  if (geo.contains("nodes")) {
    const Value nodes = rd.array_at(geo, gp, "nodes");
    const Path nodes_path = gp.key("nodes");
    t.nodes.reserve(capped(nodes.size()));
    listed.reserve(capped(nodes.size()));
    for (size_t i = 0; i < nodes.size(); ++i) {
      const Path np = nodes_path.at(i);
      const Value jn = nodes[i];
      TraceNode n;
      n.id = int32_t(rd.integer_at(jn, np, "id", 0, max_node));
      if (!listed.insert(n.id).second)
        rd.fail(np.key("id"), "node " + std::to_string(n.id) + " is listed twice");
      n.parent = int32_t(rd.integer_at(jn, np, "parent", -1, max_node));
      n.depth = int32_t(rd.integer_at(jn, np, "depth", 0, 1 << 16));
      n.box.lo = rd.vec_at(jn, np, "min");
      n.box.hi = rd.vec_at(jn, np, "max");
      const Value leaf = rd.member(jn, np, "leaf");
      if (!leaf.is_boolean()) rd.fail(np.key("leaf"), "expected true or false");
      n.leaf = leaf.get_bool();
      // Version 3: a BVH's inner node lists its children (1 to 8 distinct ids, not its own), and its axis may
      // be null (the wide BVH); a kd node has a split plane instead. Older versions had no children: ignored
      const bool has_children = version >= 3 && jn.contains("children");
      if (n.leaf) {
        const Value ids = rd.array_at(jn, np, "prims");
        const Path pp = np.key("prims");
        n.prims.reserve(capped(ids.size()));
        for (size_t k = 0; k < ids.size(); ++k)
          n.prims.push_back(int32_t(rd.integer(ids[k], pp.at(k), 0, max_prim)));
        if (has_children) rd.fail(np.key("children"), "a leaf has no children");
      } else if (has_children) {
        const Value ids = rd.array_at(jn, np, "children");
        const Path cp = np.key("children");
        if (ids.size() < 1 || ids.size() > 8) rd.fail(cp, "expected 1 to 8 child ids");
        for (size_t k = 0; k < ids.size(); ++k) {
          const int32_t c = int32_t(rd.integer(ids[k], cp.at(k), 0, max_node));
          if (c == n.id) rd.fail(cp.at(k), "a node is not its own child");
          if (std::find(n.children.begin(), n.children.end(), c) != n.children.end())
            rd.fail(cp.at(k), "child " + std::to_string(c) + " is listed twice");
          n.children.push_back(c);
        }
        n.axis = axis_index(rd, rd.member(jn, np, "axis"), np.key("axis"));
        if (octree && ((ids.size() != 8 && ids.size() != 4) || n.axis != -1))
          rd.fail(cp, "an inner octree node has 8 children (a quadtree's 4) and axis null");
        if (octree && octree_children && ids.size() != octree_children)
          rd.fail(cp, "an inner octree node has " + std::to_string(octree_children) +
                          " children, as the trace's other inner cells");
        if (octree) octree_children = ids.size();
      } else if (bsp || (version >= 4 && jn.contains("normal"))) {
        // Version 4: a BSP node's plane, a finite unit normal (to float rounding) and a finite offset.
        n.has_plane = true;
        n.normal = rd.vec_at(jn, np, "normal");
        const float len =
            std::sqrt(n.normal.x * n.normal.x + n.normal.y * n.normal.y + n.normal.z * n.normal.z);
        if (!is_finite(n.normal) || !(std::fabs(len - 1.f) <= 1e-3f))
          rd.fail(np.key("normal"), "expected a finite unit normal");
        n.offset = rd.real_at(jn, np, "offset");
        if (!std::isfinite(n.offset)) rd.fail(np.key("offset"), "expected a finite number");
      } else {
        if (lists_children)
          rd.fail(np, octree ? "missing \"children\" (an inner octree node lists its 8 children)"
                             : "missing \"children\" (an inner BVH node lists its children)");
        n.axis = axis_index(rd, rd.member(jn, np, "axis"), np.key("axis"));
        if (n.axis < 0) rd.fail(np.key("axis"), "an inner node has a split axis");
        n.split = rd.real_at(jn, np, "split");
      }
      t.nodes.push_back(std::move(n));
    }
  }
  // A BVH's nodes (version 3) hang together: each listed node's parent is listed (the chain up to the root),
  // names it among its children, and lies one level above it.
  std::unordered_map<int32_t, size_t> node_at;
  for (size_t i = 0; i < t.nodes.size(); ++i) node_at.emplace(t.nodes[i].id, i);
  if (lists_children) {
    const Path nodes_path = gp.key("nodes");
    for (size_t i = 0; i < t.nodes.size(); ++i) {
      const TraceNode& n = t.nodes[i];
      const Path np = nodes_path.at(i);
      if (n.parent < 0) {
        if (n.depth != 0) rd.fail(np.key("depth"), "the root (parent -1) has depth 0");
        continue;
      }
      auto p = node_at.find(n.parent);
      if (p == node_at.end())
        rd.fail(np.key("parent"), "node " + std::to_string(n.parent) + " is not in geometry.nodes");
      const TraceNode& parent = t.nodes[p->second];
      if (std::find(parent.children.begin(), parent.children.end(), n.id) == parent.children.end())
        rd.fail(np.key("parent"), "node " + std::to_string(n.parent) + " does not list it as a child");
      if (n.depth != parent.depth + 1)
        rd.fail(np.key("depth"), "expected " + std::to_string(parent.depth + 1) + ", one below its parent");
    }
  }
  if (t.structure.kind != "grid") {
    for (size_t r = 0; r < t.rays.size(); ++r)
      for (size_t i = 0; i < t.rays[r].events.size(); ++i) {
        const Event& e = t.rays[r].events[i];
        bool tree_event = e.type == EventType::node || e.type == EventType::push ||
                          e.type == EventType::pop || e.type == EventType::leaf ||
                          e.type == EventType::skip || e.type == EventType::box_test;
        const Path rp = rays_path.at(r);
        const Path esp = rp.key("events");
        const Path ep = esp.at(i);
        if (tree_event && !listed.count(e.node))
          rd.fail(ep.key("node"), "node " + std::to_string(e.node) + " is not in geometry.nodes");
        if (e.type == EventType::box_test) {
          const TraceNode& child = t.nodes[node_at.at(e.node)];
          if (e.parent < 0) {
            if (child.parent >= 0)
              rd.fail(ep.key("parent"), "only the root's box (node 0) is tested without a parent");
          } else {
            auto p = node_at.find(e.parent);
            if (p == node_at.end())
              rd.fail(ep.key("parent"), "node " + std::to_string(e.parent) + " is not in geometry.nodes");
            const std::vector<int32_t>& children = t.nodes[p->second].children;
            if (std::find(children.begin(), children.end(), e.node) == children.end())
              rd.fail(ep.key("node"), "node " + std::to_string(e.node) + " is not a child of node " +
                                          std::to_string(e.parent));
          }
          if (e.depth != child.depth)
            rd.fail(ep.key("depth"), "expected " + std::to_string(child.depth) + ", the depth of node " +
                                         std::to_string(e.node) + " in geometry.nodes");
        }
      }
  }

  if (doc.contains("build")) {
    const Value build = rd.array_at(doc, root, "build");
    t.build.reserve(capped(build.size()));
    const Path build_path = sub(base, "build");
    for (size_t i = 0; i < build.size(); ++i) {
      const Path bp = build_path.at(i);
      const Value jb = build[i];
      TraceBuildEvent b;
      if (rd.integer_at(jb, bp, "seq", 0, 1ll << 40) != int64_t(i))
        rd.fail(bp.key("seq"), "expected " + std::to_string(i) + " (build events are numbered in order)");
      std::string_view type = rd.view_at(jb, bp, "type");
      int type_index = name_index(type, kEventNames);
      if (type_index >= 0) b.type = EventType(type_index);
      if (type_index < 0 || (b.type != EventType::sah_candidate && b.type != EventType::split &&
                             b.type != EventType::leaf_made))
        rd.fail(bp.key("type"),
                "unknown build event type \"" + std::string(type) + "\" (sah_candidate, split, leaf_made)");
      b.node = uint32_t(rd.integer_at(jb, bp, "node", 0, std::max<int64_t>(max_node, 0)));
      if (b.type == EventType::sah_candidate) {
        SahCandidate& c = b.candidate;
        c.axis = axis_index(rd, rd.member(jb, bp, "axis"), bp.key("axis"));
        if (c.axis < 0) rd.fail(bp.key("axis"), "expected \"x\", \"y\" or \"z\"");
        c.position = rd.real_at(jb, bp, "position");
        c.n_below = uint32_t(rd.integer_at(jb, bp, "n_below", 0, UINT32_MAX));
        c.n_above = uint32_t(rd.integer_at(jb, bp, "n_above", 0, UINT32_MAX));
        c.n_planar = uint32_t(rd.integer_at(jb, bp, "n_planar", 0, UINT32_MAX));
        c.area_below = rd.real_at(jb, bp, "area_below");
        c.area_above = rd.real_at(jb, bp, "area_above");
        c.area_node = rd.real_at(jb, bp, "area_node");
        c.cost = rd.real_at(jb, bp, "cost");
        std::string_view side = rd.view_at(jb, bp, "planar_side");
        if (side != "below" && side != "above")
          rd.fail(bp.key("planar_side"), "expected \"below\" or \"above\"");
        c.planar_below = side == "below";
      } else {
        b.depth = int32_t(rd.integer_at(jb, bp, "depth", 0, 1 << 16));
        b.box.lo = rd.vec_at(jb, bp, "min");
        b.box.hi = rd.vec_at(jb, bp, "max");
        b.prims = uint32_t(rd.integer_at(jb, bp, "prims", 0, UINT32_MAX));
        b.leaf_cost = rd.real_at(jb, bp, "leaf_cost");
        if (b.type == EventType::split) {
          b.axis = axis_index(rd, rd.member(jb, bp, "axis"), bp.key("axis"));
          if (b.axis < 0) rd.fail(bp.key("axis"), "expected \"x\", \"y\" or \"z\"");
          b.position = rd.real_at(jb, bp, "position");
          b.cost = rd.real_at(jb, bp, "cost");
        } else {
          std::string reason = rd.text_at(jb, bp, "reason");
          if (!parse_leaf_reason(reason, &b.reason))
            rd.fail(bp.key("reason"), "unknown leaf reason \"" + reason + "\"");
        }
      }
      t.build.push_back(b);
    }
  }

  const Value prims = rd.array_at(geo, gp, "primitives");
  const Path prims_path = gp.key("primitives");
  t.primitives.reserve(capped(prims.size()));
  for (size_t i = 0; i < prims.size(); ++i) {
    const Path pp = prims_path.at(i);
    TracePrimitive p;
    p.id = int32_t(rd.integer_at(prims[i], pp, "id", 0, max_prim));
    std::string_view type = rd.view_at(prims[i], pp, "type");
    if (type == "triangle") {
      const Value v = rd.array_at(prims[i], pp, "vertices");
      const Path vsp = pp.key("vertices");
      if (v.size() != 3) rd.fail(vsp, "expected 3 vertices");
      for (int k = 0; k < 3; ++k) {
        const Path vp = vsp.at(k);
        if (!v[k].is_array() || v[k].size() != 3) rd.fail(vp, "expected an array of 3 numbers");
        p.v[k] =
            glm::vec3(rd.real(v[k][0], vp.at(0)), rd.real(v[k][1], vp.at(1)), rd.real(v[k][2], vp.at(2)));
      }
    } else if (type == "sphere") {
      p.type = PrimType::sphere;
      p.v[0] = rd.vec_at(prims[i], pp, "center");
      p.radius = rd.real_at(prims[i], pp, "radius");
    } else {
      rd.fail(pp.key("type"), "unknown primitive type \"" + std::string(type) + "\"");
    }
    t.primitives.push_back(p);
  }
}

}  // namespace

namespace detail {

namespace {

int parse_document(const TraceText& source, std::FILE* file, const std::string& name, bool walks_allowed,
                   std::vector<Trace>* walks) {
  const Capped capped{size_t(source.size() / 64)};
  Reader rd(name, source);
  EventStreams streams(rd);
  JsonTape tape = parse_tape(source, file, name, &streams);
  const Value doc = tape.root();
  const Path root = "trace";
  if (!doc.is_object()) rd.fail(root, "expected a JSON object");
  Value format_value = doc.find("format");
  std::string_view format =
      format_value.exists() && format_value.is_string() ? format_value.get_string() : "";
  if (format != kTraceFormat) rd.fail("format", "not a raystep trace (format must be \"raystep-trace\")");
  int64_t version = rd.integer_at(doc, root, "version", 0, 1 << 30);
  if (version == kMultiTraceVersion && !walks_allowed)
    rd.fail("version",
            "version " + std::to_string(version) +
                " holds the walks of several structures (raystep trace --accel A,B,...); this reader "
                "reads a single structure's trace, versions " +
                std::to_string(kTraceOldestVersion) + " to " + std::to_string(kTraceVersion));
  if (version < kTraceOldestVersion || version > (walks_allowed ? kMultiTraceVersion : kTraceVersion))
    rd.fail("version", "unsupported trace version " + std::to_string(version) +
                           " (this raystep reads versions " + std::to_string(kTraceOldestVersion) + " to " +
                           std::to_string(walks_allowed ? kMultiTraceVersion : kTraceVersion) + ")");

  Trace t;
  t.version = int(version);
  const Value scene = rd.member(doc, root, "scene");
  t.scene_path = rd.text_at(scene, "scene", "path");
  t.scene_hash = rd.text_at(scene, "scene", "hash");
  t.scene_primitives = uint64_t(rd.integer_at(scene, "scene", "primitives", 0, int64_t(1) << 40));
  walks->clear();
  if (version < kMultiTraceVersion) {
    read_walk(rd, doc, root, nullptr, version, t, capped, streams);
    walks->push_back(std::move(t));
    return int(version);
  }

  // Version 5: the scene once, then 2 to 6 walks, each a version 4 trace's structure, pixel, rays, geometry
  // and build, read with that version's rules; every walk traces the same rays in the same order.
  const Value jw = rd.array_at(doc, root, "walks");
  const Path walks_path = "walks";
  if (jw.size() < size_t(kMinWalks) || jw.size() > size_t(kMaxWalks))
    rd.fail(walks_path, "expected " + std::to_string(kMinWalks) + " to " + std::to_string(kMaxWalks) +
                            " walks, found " + std::to_string(jw.size()));
  walks->reserve(jw.size());
  for (size_t w = 0; w < jw.size(); ++w) {
    const Path wp = walks_path.at(w);
    Trace walk;
    walk.version = int(version);
    walk.scene_path = t.scene_path;
    walk.scene_hash = t.scene_hash;
    walk.scene_primitives = t.scene_primitives;
    read_walk(rd, jw[w], wp, &wp, kTraceVersion, walk, capped, streams);
    if (w > 0) {
      const Trace& first = walks->front();
      const Path rays_path = wp.key("rays");
      if (walk.rays.size() != first.rays.size())
        rd.fail(rays_path, std::to_string(walk.rays.size()) + " rays, but walks[0] has " +
                               std::to_string(first.rays.size()) + " (every walk traces the same rays)");
      for (size_t r = 0; r < walk.rays.size(); ++r) {
        const TracedRay& a = first.rays[r];
        const TracedRay& b = walk.rays[r];
        if (a.ray.origin != b.ray.origin || a.ray.direction != b.ray.direction || a.ray.tmin != b.ray.tmin ||
            a.ray.tmax != b.ray.tmax || a.kind != b.kind || a.depth != b.depth ||
            a.has_pixel != b.has_pixel || a.pixel[0] != b.pixel[0] || a.pixel[1] != b.pixel[1] ||
            a.sample != b.sample)
          rd.fail(rays_path.at(r), "not the same ray as walks[0].rays[" + std::to_string(r) +
                                       "] (every walk traces the same rays)");
      }
    }
    walks->push_back(std::move(walk));
  }
  return int(version);
}

}  // namespace

int parse_trace_document(const std::string& text, const std::string& name, bool walks_allowed,
                         std::vector<Trace>* walks) {
  return parse_document(TraceText(text), nullptr, name, walks_allowed, walks);
}

int read_trace_document(const std::string& path, bool walks_allowed, std::vector<Trace>* walks) {
  // A regular file only: a directory, a device such as /dev/zero or a FIFO would fail oddly, never end, or
  // block; the scene and ray readers refuse them the same way.
  std::error_code ec;
  std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw InputError(path, 0, "cannot read the file: no such file");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(path, 0, "cannot read the file: not a regular file");
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, 0, "cannot read the file");
  // Refused before a byte is read when it would not fit (util/memory_limit.h).
  if (size > 0) check_read_memory(path, InputKind::trace_json, size);
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw InputError(path, 0, "cannot read the file");
  // Streamed: the events go into their rays as they are parsed; the text is never held whole.
  return parse_document(TraceText(path, size), file.get(), path, walks_allowed, walks);
}

}  // namespace detail

Trace parse_trace_json(const std::string& text, const std::string& name) {
  std::vector<Trace> walks;
  detail::parse_trace_document(text, name, false, &walks);
  return std::move(walks.front());
}

Trace read_trace_json(const std::string& path) {
  std::vector<Trace> walks;
  detail::read_trace_document(path, false, &walks);
  return std::move(walks.front());
}

}  // namespace raystep
