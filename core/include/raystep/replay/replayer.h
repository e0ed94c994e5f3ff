// Stepping through a ray of any length: the replay state at any event, computed from the nearest checkpoint
// before it instead of from the ray's start. One pass over the events keeps, every `checkpoint_every` events,
// the walk's small state (the current cell or node, the stack, the counters, the nearest hit) and, once for
// the whole ray, the lists that only grow (cells visited, nodes left, nodes skipped, primitives tested); a
// state is then a checkpoint advanced by fewer than checkpoint_every events, plus those lists' prefixes.
// A step forward, a step back and a jump cost the same: O(checkpoint_every) plus the lists the state holds.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/replay/replay_state.h"

namespace raystep::replay {

class Replayer {
 public:
  static constexpr int kCheckpointEvery = 1024;

  // The ray must outlive the replayer. checkpoint_every >= 1 (a huge one replays from the start every time).
  explicit Replayer(const TracedRay& ray, int checkpoint_every = kCheckpointEvery);

  const TracedRay& ray() const { return *ray_; }
  int size() const { return int(ray_->events.size()); }
  // The state after event `step` (clamped to the events; an empty ray gives the empty state).
  ReplayState at(int step) const;

 private:
  // What the walk holds after some events, without the lists that only grow (those are prefixes of the
  // ray-wide lists below, by their lengths).
  struct Walk {
    int cell_event = -1, node_event = -1;
    std::vector<StackEntry> stack;
    RayCounters counters;
    int32_t nearest_prim = -1, nearest_prim_before = -1;
    float nearest_t = 0.f;
    bool deferred = false, accepted = false, ended = false;
    AcceptReason reason = AcceptReason::inside_cell;
    bool has_interval = false;
    float t_min = 0.f, t_max = 0.f;
    uint32_t left = 0, skipped = 0;  // lengths of left_ and skipped_
  };
  void advance(Walk& w, int i) const;
  int skips(size_t entry, int step) const;

  const TracedRay* ray_;
  int every_;
  std::vector<Walk> checkpoints_;    // [c]: the walk before event c * every_
  std::vector<uint8_t> grows_;       // per event: it adds to left_ (1) or skipped_ (2)
  std::vector<int> cell_events_;     // every cell event, in order
  std::vector<int32_t> left_;        // the nodes the walk left, each once, in the order it left them
  std::vector<int32_t> skipped_;     // BVH: popped entries never visited, each once
  std::vector<MailboxEntry> tests_;  // every primitive test, in order (skips 0)
  // The mailbox hits of each primitive's first test (tests_ index), by event: hits_[hit_start_[j] ..
  // hit_start_[j + 1]) for entry j.
  std::vector<uint32_t> hit_start_;
  std::vector<int> hits_;
};

}  // namespace raystep::replay
