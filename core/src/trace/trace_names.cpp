// The trace format's names (event types, accept reasons, ray kinds, axes), a ray's counters from its events,
// and the scene file's hash.
#include "raystep/trace/trace_file.h"

#include "raystep/render/pixel_filter.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include <nlohmann/json.hpp>

#include "raystep/render/pixel_filter.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/scene/json_locate.h"
#include "raystep/scene/json_tape.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"
#include "raystep/util/memory_limit.h"
#include "trace_file_detail.h"

namespace raystep {

using nlohmann::json;
using ordered = nlohmann::ordered_json;

namespace detail {

const char* const kEventNames[kEventTypeCount] = {
    "ray_begin", "cell",        "node",         "push",         "pop",     "leaf",
    "prim_test", "mailbox_hit", "hit_deferred", "hit_accepted", "ray_end", "sah_candidate",
    "split",     "leaf_made",   "box_test",     "skip"};
const char* const kReasonNames[kAcceptReasonCount] = {"inside_cell", "any_hit", "structure_done",
                                                      "next_node_beyond"};
const char* const kRayKinds[4] = {"primary", "shadow", "reflected", "refracted"};
const char* const kAxes[3] = {"x", "y", "z"};
const char* const kOutcomes[3] = {"agree", "depth_limit", "subdivided"};  // AdaptiveSquare::Outcome

// A ray's counters from its events, as the kernels count them.
RayCounters count_events(const std::vector<Event>& events) {
  RayCounters c;
  for (const Event& e : events) {
    switch (e.type) {
      case EventType::cell:
        ++c.cells;
        break;
      case EventType::node:
        ++c.nodes;
        break;
      case EventType::push:
        ++c.pushes;
        break;
      case EventType::pop:
        ++c.pops;
        break;
      case EventType::prim_test:
        ++c.prim_tests;
        c.prim_hits += e.hit;
        break;
      case EventType::mailbox_hit:
        ++c.mailbox_hits;
        break;
      case EventType::box_test:
        ++c.box_tests;
        break;
      default:
        break;
    }
  }
  return c;
}

}  // namespace detail

using namespace detail;

const char* event_type_name(EventType type) {
  return kEventNames[int(type)];
}

bool parse_event_type(const std::string& name, EventType* type) {
  const int i = name_index(name, kEventNames);
  if (i >= 0) *type = EventType(i);
  return i >= 0;
}

const char* accept_reason_name(AcceptReason reason) {
  return kReasonNames[int(reason)];
}

bool parse_accept_reason(const std::string& name, AcceptReason* reason) {
  const int i = name_index(name, kReasonNames);
  if (i >= 0) *reason = AcceptReason(i);
  return i >= 0;
}

const char* ray_kind_name(RayKind kind) {
  return kRayKinds[int(kind)];
}

bool parse_leaf_reason(const std::string& name, LeafReason* reason) {
  for (LeafReason r : {LeafReason::few_primitives, LeafReason::max_depth, LeafReason::no_cheaper_split,
                       LeafReason::no_candidate, LeafReason::budget})
    if (name == leaf_reason_name(r)) {
      *reason = r;
      return true;
    }
  return false;
}

std::string file_content_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot read the file");
  uint64_t h = 1469598103934665603ull;
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= uint8_t(buf[i]);
      h *= 1099511628211ull;
    }
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return std::string("fnv1a64:") + hex;
}

}  // namespace raystep
