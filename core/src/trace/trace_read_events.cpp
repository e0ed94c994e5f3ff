// Reading a trace's events: each event object checked as it is parsed (trace_reader.h's EventStreams gets
// them one at a time from the JSON parser, so a ray of ten million events is never held as text or as a parse
// tape), then the numbers that depend on the rest of the document (the grid's resolution, the node and
// primitive counts, the version) checked once it is read.
#include <string>
#include <vector>

#include "trace_reader.h"

namespace raystep::detail {

int axis_index(const Reader& rd, const Value& v, const Path& path) {
  if (v.is_null()) return -1;
  int a = v.is_string() ? name_index(v.get_string(), kAxes) : -1;
  if (a < 0) rd.fail(path, "expected \"x\", \"y\", \"z\" or null");
  return a;
}

Event read_event(const Reader& rd, const Value& je, const Path& ep, size_t i, const EventLimits& lim) {
  Event e;
  e.seq = uint32_t(rd.integer_at(je, ep, "seq", 0, 1ll << 32));
  if (e.seq != i) rd.fail(ep.key("seq"), "expected " + std::to_string(i) + " (events are numbered in order)");
  std::string_view type = rd.view_at(je, ep, "type");
  int type_index = name_index(type, kEventNames);
  if (type_index < 0) rd.fail(ep.key("type"), "unknown event type \"" + std::string(type) + "\"");
  e.type = EventType(type_index);
  if (lim.version < 3 && (e.type == EventType::box_test || e.type == EventType::skip))
    rd.fail(ep.key("type"), "event type \"" + std::string(type) + "\" needs version 3");
  switch (e.type) {
    case EventType::cell: {
      const Value c = rd.array_at(je, ep, "cell");
      const Path cp = ep.key("cell");
      if (c.size() != 3) rd.fail(cp, "expected [i, j, k]");
      for (int a = 0; a < 3; ++a)
        e.cell[a] = int(rd.integer(c[a], cp.at(a), 0, lim.grid ? lim.resolution[a] - 1 : (1 << 20)));
      e.t_enter = rd.real_at(je, ep, "t_enter");
      e.t_exit = rd.real_at(je, ep, "t_exit");
      e.t_max = rd.vec_at(je, ep, "t_max");
      e.t_delta = rd.vec_at(je, ep, "t_delta");
      e.next_axis = axis_index(rd, rd.member(je, ep, "next_axis"), ep.key("next_axis"));
      break;
    }
    case EventType::node:
    case EventType::push:
    case EventType::pop:
    case EventType::leaf:
    case EventType::skip:
      e.node = int32_t(rd.integer_at(je, ep, "node", 0, lim.max_node));
      e.depth = int32_t(rd.integer_at(je, ep, "depth", 0, 1 << 16));
      e.t_min_node = rd.real_at(je, ep, "t_min");
      e.t_max_node = rd.real_at(je, ep, "t_max");
      break;
    case EventType::box_test: {
      // A child's box tested from its parent (-1: the root's box, tested first): [t_near, t_far] on a
      // hit, finite (boxes are) and in order.
      e.parent = int32_t(rd.integer_at(je, ep, "parent", -1, lim.max_node));
      e.node = int32_t(rd.integer_at(je, ep, "node", 0, lim.max_node));
      if (e.node == e.parent) rd.fail(ep.key("node"), "a node is not its own child");
      e.depth = int32_t(rd.integer_at(je, ep, "depth", 0, 1 << 16));
      const Value h = rd.member(je, ep, "hit");
      if (!h.is_boolean()) rd.fail(ep.key("hit"), "expected true or false");
      e.hit = h.get_bool();
      if (e.hit) {
        e.t_min_node = rd.real_at(je, ep, "t_near");
        if (!std::isfinite(e.t_min_node)) rd.fail(ep.key("t_near"), "expected a finite number");
        e.t_max_node = rd.real_at(je, ep, "t_far");
        if (!std::isfinite(e.t_max_node)) rd.fail(ep.key("t_far"), "expected a finite number");
        if (e.t_max_node < e.t_min_node) rd.fail(ep.key("t_far"), "below t_near");
      }
      break;
    }
    case EventType::prim_test: {
      e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, lim.max_prim));
      const Value h = rd.member(je, ep, "hit");
      if (!h.is_boolean()) rd.fail(ep.key("hit"), "expected true or false");
      e.hit = h.get_bool();
      if (e.hit) e.t = rd.real_at(je, ep, "t");
      break;
    }
    case EventType::mailbox_hit:
      e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, lim.max_prim));
      break;
    case EventType::hit_deferred:
      e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, lim.max_prim));
      e.t = rd.real_at(je, ep, "t");
      e.t_exit = rd.real_at(je, ep, "t_exit");
      break;
    case EventType::hit_accepted: {
      e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, lim.max_prim));
      e.t = rd.real_at(je, ep, "t");
      std::string_view reason = rd.view_at(je, ep, "reason");
      int reason_index = name_index(reason, kReasonNames);
      if (reason_index < 0) rd.fail(ep.key("reason"), "unknown reason \"" + std::string(reason) + "\"");
      e.reason = AcceptReason(reason_index);
      break;
    }
    case EventType::ray_end:
      e.prim = int32_t(rd.integer_at(je, ep, "prim", -1, lim.max_prim));
      e.hit = e.prim >= 0;
      e.t = rd.real_at(je, ep, "t");
      break;
    default:
      break;
  }
  return e;
}

void check_events(const Reader& rd, const std::vector<Event>& events, const Path& events_path,
                  const EventLimits& lim) {
  // As Reader::integer says it.
  auto range = [&](int64_t v, int64_t lo, int64_t hi, const Path& p) {
    if (v < lo || v > hi)
      rd.fail(p, "value " + std::to_string(v) + " out of range " + std::to_string(lo) + ".." +
                     std::to_string(hi));
  };
  for (size_t i = 0; i < events.size(); ++i) {
    const Event& e = events[i];
    const Path ep = events_path.at(i);
    if (lim.version < 3 && (e.type == EventType::box_test || e.type == EventType::skip))
      rd.fail(ep.key("type"), std::string("event type \"") + event_type_name(e.type) + "\" needs version 3");
    switch (e.type) {
      case EventType::cell:
        if (lim.grid) {
          const Path cp = ep.key("cell");
          for (int a = 0; a < 3; ++a) range(e.cell[a], 0, lim.resolution[a] - 1, cp.at(size_t(a)));
        }
        break;
      case EventType::node:
      case EventType::push:
      case EventType::pop:
      case EventType::leaf:
      case EventType::skip:
        range(e.node, 0, lim.max_node, ep.key("node"));
        break;
      case EventType::box_test:
        range(e.parent, -1, lim.max_node, ep.key("parent"));
        range(e.node, 0, lim.max_node, ep.key("node"));
        break;
      case EventType::prim_test:
      case EventType::mailbox_hit:
      case EventType::hit_deferred:
      case EventType::hit_accepted:
        range(e.prim, 0, lim.max_prim, ep.key("prim"));
        break;
      case EventType::ray_end:
        range(e.prim, -1, lim.max_prim, ep.key("prim"));
        break;
      default:
        break;
    }
  }
}

bool EventStreams::stream(std::string_view path) {
  return path == "rays[].events" || path == "walks[].rays[].events";
}

void EventStreams::element(size_t array, const std::vector<size_t>& where, const JsonValue& value) {
  if (streams_.size() <= array) streams_.resize(array + 1);
  Stream& s = streams_[array];
  if (s.chunks.empty() || s.chunks.back().size() == kChunk) {
    s.chunks.emplace_back();
    s.chunks.back().reserve(kChunk);
  }
  // The element's path, for an error's message: "rays[r].events[i]" (versions 1 to 4) or
  // "walks[w].rays[r].events[i]" (version 5).
  const size_t i = where.back();
  const Path rays("rays"), walks("walks"), wp = walks.at(where[0]), walk_rays = wp.key("rays");
  const Path rp = where.size() == 2 ? rays.at(where[0]) : walk_rays.at(where[1]);
  const Path ev = rp.key("events"), ep = ev.at(i);
  s.chunks.back().push_back(read_event(rd_, value, ep, i, EventLimits{}));
}

void EventStreams::end(size_t array, size_t count) {
  if (streams_.size() <= array) streams_.resize(array + 1);
  Stream& s = streams_[array];
  // One vector of exactly its events, each chunk let go as soon as it is copied: the events are held once.
  s.events.reserve(count);
  for (std::vector<Event>& c : s.chunks) {
    s.events.insert(s.events.end(), c.begin(), c.end());
    std::vector<Event>().swap(c);
  }
  s.chunks.clear();
}

std::vector<Event> EventStreams::take(size_t array) {
  if (array >= streams_.size()) return {};
  return std::move(streams_[array].events);
}

}  // namespace raystep::detail
