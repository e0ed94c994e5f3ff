// The trace reader as it was before the tape (nlohmann-json DOM, commit b4d758d), kept verbatim as the reference
// that the fast reader is tested against: on any text both return the same trace or throw the same error.
#pragma once

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "raystep/scene/json_locate.h"
#include "raystep/trace/trace_file.h"
#include "raystep/util/error.h"

namespace raystep {
namespace reference {

using nlohmann::json;

const char* const kRayKinds[4] = {"primary", "shadow", "reflected", "refracted"};
const char* const kAxes[3] = {"x", "y", "z"};


// Walks a parsed document with the JSON path of every value, so that errors say where.
class Reader {
 public:
  Reader(const std::string& name, const std::string& text) : name_(name), text_(text) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError(name_, line_of(path), path + ": " + what);
  }

  const json& member(const json& obj, const std::string& path, const char* key) const {
    if (!obj.is_object()) fail(path, "expected an object");
    auto it = obj.find(key);
    if (it == obj.end()) fail(path, std::string("missing \"") + key + "\"");
    return *it;
  }
  float real(const json& v, const std::string& path) const {
    if (v.is_string()) {
      if (v == "inf") return kInfinity;
      if (v == "-inf") return -kInfinity;
    }
    if (!v.is_number()) fail(path, v.is_null() ? "expected a number, found null (NaN?)" : "expected a number");
    double d = v.get<double>();
    if (!std::isfinite(d) || std::fabs(d) > 3.4028234663852886e38) fail(path, "number out of float range");
    return float(d);
  }
  float real_at(const json& obj, const std::string& path, const char* key) const {
    return real(member(obj, path, key), path + "." + key);
  }
  int64_t integer(const json& v, const std::string& path, int64_t lo, int64_t hi) const {
    if (!v.is_number_integer()) fail(path, "expected an integer");
    int64_t i = v.get<int64_t>();
    if (i < lo || i > hi)
      fail(path, "value " + std::to_string(i) + " out of range " + std::to_string(lo) + ".." + std::to_string(hi));
    return i;
  }
  int64_t integer_at(const json& obj, const std::string& path, const char* key, int64_t lo, int64_t hi) const {
    return integer(member(obj, path, key), path + "." + key, lo, hi);
  }
  std::string text_at(const json& obj, const std::string& path, const char* key) const {
    const json& v = member(obj, path, key);
    if (!v.is_string()) fail(path + "." + key, "expected a string");
    return v.get<std::string>();
  }
  glm::vec3 vec_at(const json& obj, const std::string& path, const char* key) const {
    const json& v = member(obj, path, key);
    std::string p = path + "." + key;
    if (!v.is_array() || v.size() != 3) fail(p, "expected an array of 3 numbers");
    return glm::vec3(real(v[0], p + "[0]"), real(v[1], p + "[1]"), real(v[2], p + "[2]"));
  }
  const json& array_at(const json& obj, const std::string& path, const char* key) const {
    const json& v = member(obj, path, key);
    if (!v.is_array()) fail(path + "." + key, "expected an array");
    return v;
  }

 private:
  // The line where the value at a path like rays[0].events[3].prim starts (only when reporting an error).
  int line_of(const std::string& path) const;

  std::string name_;
  const std::string& text_;
};

// The line of a value named in display form ("rays[0].events[3].prim"): converted to a JSON pointer.
inline int Reader::line_of(const std::string& path) const {
  std::string pointer;
  std::string rest = path.rfind("trace", 0) == 0 ? path.substr(5) : path;
  for (char c : rest) {
    if (c == '.' || c == '[') pointer += '/';
    else if (c != ']') pointer += c;
  }
  if (!pointer.empty() && pointer[0] != '/') pointer.insert(pointer.begin(), '/');
  return json_line_of(text_, pointer);
}


inline Trace parse_trace_json(const std::string& text, const std::string& name) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    int line = json_line_at_byte(text, e.byte);
    bool truncated = e.byte >= text.size();
    throw InputError(name, line, truncated ? "the trace is truncated (unexpected end of the file)"
                                           : std::string("malformed JSON: ") + e.what());
  }
  Reader rd(name, text);
  const std::string root = "trace";
  if (!doc.is_object()) rd.fail(root, "expected a JSON object");
  std::string format = doc.contains("format") && doc["format"].is_string() ? doc["format"].get<std::string>() : "";
  if (format != kTraceFormat) rd.fail("format", "not a raystep trace (format must be \"raystep-trace\")");
  int64_t version = rd.integer_at(doc, root, "version", 0, 1 << 30);
  if (version != kTraceVersion)
    rd.fail("version", "unsupported trace version " + std::to_string(version) + " (this raystep reads version " +
                           std::to_string(kTraceVersion) + ")");

  Trace t;
  const json& scene = rd.member(doc, root, "scene");
  t.scene_path = rd.text_at(scene, "scene", "path");
  t.scene_hash = rd.text_at(scene, "scene", "hash");
  t.scene_primitives = uint64_t(rd.integer_at(scene, "scene", "primitives", 0, int64_t(1) << 40));

  const json& st = rd.member(doc, root, "structure");
  t.structure.kind = rd.text_at(st, "structure", "kind");
  t.structure.bounds.lo = rd.vec_at(st, "structure", "bounds_min");
  t.structure.bounds.hi = rd.vec_at(st, "structure", "bounds_max");
  bool grid = t.structure.kind == "grid";
  if (grid) {
    const json& res = rd.array_at(st, "structure", "resolution");
    if (res.size() != 3) rd.fail("structure.resolution", "expected [nx, ny, nz]");
    for (int a = 0; a < 3; ++a)
      t.structure.resolution[a] = int(rd.integer(res[a], "structure.resolution[" + std::to_string(a) + "]", 1, 4096));
  }
  for (auto it = st.begin(); it != st.end(); ++it) {
    if (it.key() == "kind" || it.key() == "bounds_min" || it.key() == "bounds_max" || it.key() == "resolution")
      continue;
    TraceParam p;
    p.key = it.key();
    if (it->is_string()) {
      p.is_text = true;
      p.text = it->get<std::string>();
    } else {
      p.number = rd.real(*it, "structure." + it.key());
    }
    t.structure.params.push_back(p);
  }

  const int64_t max_prim = int64_t(t.scene_primitives) - 1;
  int64_t max_node = INT32_MAX;  // trees: ids below the structure's node count, when it gives one
  for (const TraceParam& p : t.structure.params)
    if (p.key == "nodes" && !p.is_text) max_node = std::min<int64_t>(int64_t(p.number) - 1, INT32_MAX);
  auto axis_index = [&](const json& v, const std::string& path) {
    if (v.is_null()) return -1;
    for (int a = 0; a < 3; ++a)
      if (v == kAxes[a]) return a;
    rd.fail(path, "expected \"x\", \"y\", \"z\" or null");
  };

  const json& rays = rd.array_at(doc, root, "rays");
  for (size_t r = 0; r < rays.size(); ++r) {
    std::string rp = "rays[" + std::to_string(r) + "]";
    const json& jr = rays[r];
    TracedRay tr;
    tr.ray.origin = rd.vec_at(jr, rp, "origin");
    tr.ray.direction = rd.vec_at(jr, rp, "direction");
    tr.ray.tmin = rd.real_at(jr, rp, "tmin");
    tr.ray.tmax = rd.real_at(jr, rp, "tmax");
    std::string kind = rd.text_at(jr, rp, "kind");
    bool known_kind = false;
    for (int k = 0; k < 4; ++k)
      if (kind == kRayKinds[k]) {
        tr.kind = RayKind(k);
        known_kind = true;
      }
    if (!known_kind) rd.fail(rp + ".kind", "unknown ray kind \"" + kind + "\"");
    tr.depth = int(rd.integer_at(jr, rp, "depth", 0, 1000));
    if (jr.contains("pixel")) {
      const json& px = jr["pixel"];
      if (!px.is_array() || px.size() != 2) rd.fail(rp + ".pixel", "expected [x, y]");
      tr.has_pixel = true;
      tr.pixel[0] = int(rd.integer(px[0], rp + ".pixel[0]", 0, 1 << 20));
      tr.pixel[1] = int(rd.integer(px[1], rp + ".pixel[1]", 0, 1 << 20));
    }
    const json& events = rd.array_at(jr, rp, "events");
    for (size_t i = 0; i < events.size(); ++i) {
      std::string ep = rp + ".events[" + std::to_string(i) + "]";
      const json& je = events[i];
      Event e;
      e.seq = uint32_t(rd.integer_at(je, ep, "seq", 0, 1ll << 32));
      if (e.seq != i) rd.fail(ep + ".seq", "expected " + std::to_string(i) + " (events are numbered in order)");
      std::string type = rd.text_at(je, ep, "type");
      if (!parse_event_type(type, &e.type)) rd.fail(ep + ".type", "unknown event type \"" + type + "\"");
      switch (e.type) {
        case EventType::cell: {
          const json& c = rd.array_at(je, ep, "cell");
          if (c.size() != 3) rd.fail(ep + ".cell", "expected [i, j, k]");
          for (int a = 0; a < 3; ++a)
            e.cell[a] = int(rd.integer(c[a], ep + ".cell[" + std::to_string(a) + "]", 0,
                                       grid ? t.structure.resolution[a] - 1 : (1 << 20)));
          e.t_enter = rd.real_at(je, ep, "t_enter");
          e.t_exit = rd.real_at(je, ep, "t_exit");
          e.t_max = rd.vec_at(je, ep, "t_max");
          e.t_delta = rd.vec_at(je, ep, "t_delta");
          e.next_axis = axis_index(rd.member(je, ep, "next_axis"), ep + ".next_axis");
          break;
        }
        case EventType::node:
        case EventType::push:
        case EventType::pop:
        case EventType::leaf:
          e.node = int32_t(rd.integer_at(je, ep, "node", 0, max_node));
          e.depth = int32_t(rd.integer_at(je, ep, "depth", 0, 1 << 16));
          e.t_min_node = rd.real_at(je, ep, "t_min");
          e.t_max_node = rd.real_at(je, ep, "t_max");
          break;
        case EventType::prim_test: {
          e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, max_prim));
          const json& h = rd.member(je, ep, "hit");
          if (!h.is_boolean()) rd.fail(ep + ".hit", "expected true or false");
          e.hit = h.get<bool>();
          if (e.hit) e.t = rd.real_at(je, ep, "t");
          break;
        }
        case EventType::mailbox_hit:
          e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, max_prim));
          break;
        case EventType::hit_deferred:
          e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, max_prim));
          e.t = rd.real_at(je, ep, "t");
          e.t_exit = rd.real_at(je, ep, "t_exit");
          break;
        case EventType::hit_accepted: {
          e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, max_prim));
          e.t = rd.real_at(je, ep, "t");
          std::string reason = rd.text_at(je, ep, "reason");
          if (!parse_accept_reason(reason, &e.reason)) rd.fail(ep + ".reason", "unknown reason \"" + reason + "\"");
          break;
        }
        case EventType::ray_end:
          e.prim = int32_t(rd.integer_at(je, ep, "prim", -1, max_prim));
          e.hit = e.prim >= 0;
          e.t = rd.real_at(je, ep, "t");
          break;
        default:
          break;
      }
      tr.events.push_back(e);
    }
    if (tr.events.empty() || tr.events.front().type != EventType::ray_begin ||
        tr.events.back().type != EventType::ray_end)
      rd.fail(rp + ".events", "a ray's events start with ray_begin and end with ray_end");
    t.rays.push_back(std::move(tr));
  }

  const json& geo = rd.member(doc, root, "geometry");
  const json& cells = rd.array_at(geo, "geometry", "cells");
  for (size_t i = 0; i < cells.size(); ++i) {
    std::string cp = "geometry.cells[" + std::to_string(i) + "]";
    TraceCell c;
    const json& idx = rd.array_at(cells[i], cp, "cell");
    if (idx.size() != 3) rd.fail(cp + ".cell", "expected [i, j, k]");
    for (int a = 0; a < 3; ++a)
      c.cell[a] = int(rd.integer(idx[a], cp + ".cell[" + std::to_string(a) + "]", 0,
                                 grid ? t.structure.resolution[a] - 1 : (1 << 20)));
    c.box.lo = rd.vec_at(cells[i], cp, "min");
    c.box.hi = rd.vec_at(cells[i], cp, "max");
    t.cells.push_back(c);
  }
  // Tree nodes: ids below the structure's node count, each listed once, every node an event names listed.
  std::set<int32_t> listed;
  if (geo.contains("nodes")) {
    const json& nodes = rd.array_at(geo, "geometry", "nodes");
    for (size_t i = 0; i < nodes.size(); ++i) {
      std::string np = "geometry.nodes[" + std::to_string(i) + "]";
      const json& jn = nodes[i];
      TraceNode n;
      n.id = int32_t(rd.integer_at(jn, np, "id", 0, max_node));
      if (!listed.insert(n.id).second) rd.fail(np + ".id", "node " + std::to_string(n.id) + " is listed twice");
      n.parent = int32_t(rd.integer_at(jn, np, "parent", -1, max_node));
      n.depth = int32_t(rd.integer_at(jn, np, "depth", 0, 1 << 16));
      n.box.lo = rd.vec_at(jn, np, "min");
      n.box.hi = rd.vec_at(jn, np, "max");
      const json& leaf = rd.member(jn, np, "leaf");
      if (!leaf.is_boolean()) rd.fail(np + ".leaf", "expected true or false");
      n.leaf = leaf.get<bool>();
      if (n.leaf) {
        const json& ids = rd.array_at(jn, np, "prims");
        for (size_t k = 0; k < ids.size(); ++k)
          n.prims.push_back(int32_t(rd.integer(ids[k], np + ".prims[" + std::to_string(k) + "]", 0, max_prim)));
      } else {
        n.axis = axis_index(rd.member(jn, np, "axis"), np + ".axis");
        if (n.axis < 0) rd.fail(np + ".axis", "an inner node has a split axis");
        n.split = rd.real_at(jn, np, "split");
      }
      t.nodes.push_back(std::move(n));
    }
  }
  if (t.structure.kind != "grid") {
    for (size_t r = 0; r < t.rays.size(); ++r)
      for (size_t i = 0; i < t.rays[r].events.size(); ++i) {
        const Event& e = t.rays[r].events[i];
        bool tree_event = e.type == EventType::node || e.type == EventType::push || e.type == EventType::pop ||
                          e.type == EventType::leaf;
        if (tree_event && !listed.count(e.node))
          rd.fail("rays[" + std::to_string(r) + "].events[" + std::to_string(i) + "].node",
                  "node " + std::to_string(e.node) + " is not in geometry.nodes");
      }
  }

  if (doc.contains("build")) {
    const json& build = rd.array_at(doc, root, "build");
    for (size_t i = 0; i < build.size(); ++i) {
      std::string bp = "build[" + std::to_string(i) + "]";
      const json& jb = build[i];
      TraceBuildEvent b;
      if (rd.integer_at(jb, bp, "seq", 0, 1ll << 40) != int64_t(i))
        rd.fail(bp + ".seq", "expected " + std::to_string(i) + " (build events are numbered in order)");
      std::string type = rd.text_at(jb, bp, "type");
      if (!parse_event_type(type, &b.type) ||
          (b.type != EventType::sah_candidate && b.type != EventType::split && b.type != EventType::leaf_made))
        rd.fail(bp + ".type", "unknown build event type \"" + type + "\" (sah_candidate, split, leaf_made)");
      b.node = uint32_t(rd.integer_at(jb, bp, "node", 0, std::max<int64_t>(max_node, 0)));
      if (b.type == EventType::sah_candidate) {
        SahCandidate& c = b.candidate;
        c.axis = axis_index(rd.member(jb, bp, "axis"), bp + ".axis");
        if (c.axis < 0) rd.fail(bp + ".axis", "expected \"x\", \"y\" or \"z\"");
        c.position = rd.real_at(jb, bp, "position");
        c.n_below = uint32_t(rd.integer_at(jb, bp, "n_below", 0, UINT32_MAX));
        c.n_above = uint32_t(rd.integer_at(jb, bp, "n_above", 0, UINT32_MAX));
        c.n_planar = uint32_t(rd.integer_at(jb, bp, "n_planar", 0, UINT32_MAX));
        c.area_below = rd.real_at(jb, bp, "area_below");
        c.area_above = rd.real_at(jb, bp, "area_above");
        c.area_node = rd.real_at(jb, bp, "area_node");
        c.cost = rd.real_at(jb, bp, "cost");
        std::string side = rd.text_at(jb, bp, "planar_side");
        if (side != "below" && side != "above") rd.fail(bp + ".planar_side", "expected \"below\" or \"above\"");
        c.planar_below = side == "below";
      } else {
        b.depth = int32_t(rd.integer_at(jb, bp, "depth", 0, 1 << 16));
        b.box.lo = rd.vec_at(jb, bp, "min");
        b.box.hi = rd.vec_at(jb, bp, "max");
        b.prims = uint32_t(rd.integer_at(jb, bp, "prims", 0, UINT32_MAX));
        b.leaf_cost = rd.real_at(jb, bp, "leaf_cost");
        if (b.type == EventType::split) {
          b.axis = axis_index(rd.member(jb, bp, "axis"), bp + ".axis");
          if (b.axis < 0) rd.fail(bp + ".axis", "expected \"x\", \"y\" or \"z\"");
          b.position = rd.real_at(jb, bp, "position");
          b.cost = rd.real_at(jb, bp, "cost");
        } else {
          std::string reason = rd.text_at(jb, bp, "reason");
          if (!parse_leaf_reason(reason, &b.reason)) rd.fail(bp + ".reason", "unknown leaf reason \"" + reason + "\"");
        }
      }
      t.build.push_back(b);
    }
  }

  const json& prims = rd.array_at(geo, "geometry", "primitives");
  for (size_t i = 0; i < prims.size(); ++i) {
    std::string pp = "geometry.primitives[" + std::to_string(i) + "]";
    TracePrimitive p;
    p.id = int32_t(rd.integer_at(prims[i], pp, "id", 0, max_prim));
    std::string type = rd.text_at(prims[i], pp, "type");
    if (type == "triangle") {
      const json& v = rd.array_at(prims[i], pp, "vertices");
      if (v.size() != 3) rd.fail(pp + ".vertices", "expected 3 vertices");
      for (int k = 0; k < 3; ++k) {
        std::string vp = pp + ".vertices[" + std::to_string(k) + "]";
        if (!v[k].is_array() || v[k].size() != 3) rd.fail(vp, "expected an array of 3 numbers");
        p.v[k] = glm::vec3(rd.real(v[k][0], vp + "[0]"), rd.real(v[k][1], vp + "[1]"), rd.real(v[k][2], vp + "[2]"));
      }
    } else if (type == "sphere") {
      p.type = PrimType::sphere;
      p.v[0] = rd.vec_at(prims[i], pp, "center");
      p.radius = rd.real_at(prims[i], pp, "radius");
    } else {
      rd.fail(pp + ".type", "unknown primitive type \"" + type + "\"");
    }
    t.primitives.push_back(p);
  }
  return t;
}

}  // namespace reference
}  // namespace raystep
