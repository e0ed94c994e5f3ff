#include "raystep/trace/build_event_writer.h"

namespace raystep {

namespace {
TraceBuildEvent node_event(EventType type, uint32_t node, const KdNodeInfo& info, uint32_t n,
                           float leaf_cost) {
  TraceBuildEvent b;
  b.type = type;
  b.node = node;
  b.depth = info.depth;
  b.box = info.box;
  b.prims = n;
  b.leaf_cost = leaf_cost;
  return b;
}
}  // namespace

void BuildEventListener::sah_candidate(uint32_t node, const SahCandidate& c) {
  TraceBuildEvent b;
  b.type = EventType::sah_candidate;
  b.node = node;
  b.candidate = c;
  add(b);
}

void BuildEventListener::split(uint32_t node, const KdNodeInfo& info, uint32_t n, int axis, float position,
                               float cost, float leaf_cost) {
  TraceBuildEvent b = node_event(EventType::split, node, info, n, leaf_cost);
  b.axis = axis;
  b.position = position;
  b.cost = cost;
  add(b);
}

void BuildEventListener::leaf_made(uint32_t node, const KdNodeInfo& info, uint32_t n, float leaf_cost,
                                   LeafReason reason) {
  TraceBuildEvent b = node_event(EventType::leaf_made, node, info, n, leaf_cost);
  b.reason = reason;
  add(b);
}

void BuildEventWriter::add(const TraceBuildEvent& event) {
  out_ << (count_ ? ",\n  " : "\n  ") << build_event_json(event, count_);
  ++count_;
}

}  // namespace raystep
