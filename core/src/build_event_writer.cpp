#include "raystep/trace/build_event_writer.h"

#include "raystep/trace/trace_file.h"

namespace raystep {

namespace {
TraceBuildEvent node_event(EventType type, uint32_t node, const KdNodeInfo& info, uint32_t n, float leaf_cost) {
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

void BuildEventWriter::sah_candidate(uint32_t node, const SahCandidate& c) {
  TraceBuildEvent b;
  b.type = EventType::sah_candidate;
  b.node = node;
  b.candidate = c;
  out_ << (count_ ? ",\n  " : "\n  ") << build_event_json(b, count_);
  ++count_;
}

void BuildEventWriter::split(uint32_t node, const KdNodeInfo& info, uint32_t n, int axis, float position,
                             float cost, float leaf_cost) {
  TraceBuildEvent b = node_event(EventType::split, node, info, n, leaf_cost);
  b.axis = axis;
  b.position = position;
  b.cost = cost;
  out_ << (count_ ? ",\n  " : "\n  ") << build_event_json(b, count_);
  ++count_;
}

void BuildEventWriter::leaf_made(uint32_t node, const KdNodeInfo& info, uint32_t n, float leaf_cost,
                                 LeafReason reason) {
  TraceBuildEvent b = node_event(EventType::leaf_made, node, info, n, leaf_cost);
  b.reason = reason;
  out_ << (count_ ? ",\n  " : "\n  ") << build_event_json(b, count_);
  ++count_;
}

}  // namespace raystep
