// The replay model: what a debugger shows after the first `step + 1` events of one traced ray: the current
// cell or node, the stack, the mailbox, the primitives of the current cell or leaf, the nearest hit and the
// counters. Computed from the events alone (no scene, no structure), so stepping back and forth always gives
// the same state; replay/replayer.h gets it from a checkpoint near the step. Plain C++, like the trace.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raystep/trace/trace_file.h"

namespace raystep::replay {

// The state of a primitive referenced by the current cell (or, later, leaf).
enum class PrimState { pending, testing, hit, missed, skipped };
const char* prim_state_name(PrimState s);

struct PrimMark {
  int32_t prim = -1;
  PrimState state = PrimState::pending;
  float t = 0.f;     // for hit
  bool hit = false;  // a test's result, known at its own event: the one being tested is drawn with it
};

// One mailbox entry: a primitive tested for this ray, where and with what result.
struct MailboxEntry {
  int32_t prim = -1;
  int tested_in_cell_event = -1;  // index of the cell event during which it was tested
  int cell[3] = {0, 0, 0};
  int32_t leaf = -1;  // trees: the leaf it was tested in
  bool hit = false;
  float t = 0.f;
  int skips = 0;  // mailbox hits so far
};

// Trees: an entry of the traversal stack (the far child pushed, with its interval).
struct StackEntry {
  int32_t node = -1;
  int32_t depth = 0;
  float t_min = 0.f, t_max = 0.f;
  int push_event = -1;  // index of the push event
};

struct ReplayState {
  int step = -1;  // index of the current event
  const Event* event = nullptr;
  // Grid: the current cell event (index into events, -1: none yet) and the cells visited before it.
  int cell_event = -1;
  std::vector<int> visited_cell_events;
  // The current tree node: the last node, leaf or pop event (at a push it is still the inner node being
  // split), -1: none; and the stack: the pushes not yet popped, top last.
  int node_event = -1;
  std::vector<StackEntry> stack;
  // The nodes the walk was at before the current one, each once, in the order it left them.
  std::vector<int32_t> visited_nodes;
  // BVH: popped entries not visited (their t_near beyond the nearest hit), in order.
  std::vector<int32_t> skipped_nodes;
  // The primitives of the current cell (or leaf), the block of events from block_event to the next cell:
  // every one it references, in the order the walk meets them.
  int block_event = -1;
  std::vector<PrimMark> prims;
  std::vector<MailboxEntry> mailbox;  // in test order
  RayCounters counters;
  // The nearest hit so far and whether it is final.
  int32_t nearest_prim = -1;
  float nearest_t = 0.f;
  int32_t nearest_prim_before =
      -1;  // the nearest hit before the current event (a repeated test's hit is no news)
  bool deferred = false, accepted = false, ended = false;
  AcceptReason reason = AcceptReason::inside_cell;
  // The ray's current interval [t_min, t_max]: the cell's (grid) or the current node's (tree); valid when
  // has_interval.
  bool has_interval = false;
  float t_min = 0.f, t_max = 0.f;
};

// The state after event `step` (clamped to the events), replayed from the ray's start. To step through a long
// ray, keep a Replayer (replay/replayer.h) instead: it starts from a checkpoint near the step.
ReplayState replay_at(const TracedRay& ray, int step);

// A tree walk's event: node, push, pop, leaf, box_test or skip.
bool is_tree_event(EventType type);
// True when the ray walked a tree (it has tree events).
bool is_tree_ray(const TracedRay& ray);
// Index of the next (forward) or previous event of `type` after/before `from`; -1 when there is none.
int find_event(const TracedRay& ray, int from, EventType type, bool forward);
// Index of the k-th (1-based) event of `type`; -1 when there are fewer.
int nth_event(const TracedRay& ray, EventType type, int k);

const char* axis_name(int axis);  // "x", "y", "z", or "none" for -1

}  // namespace raystep::replay
