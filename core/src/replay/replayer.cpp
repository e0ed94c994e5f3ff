#include "raystep/replay/replayer.h"

#include <algorithm>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace raystep::replay {

namespace {

constexpr uint8_t kLeaves = 1, kSkips = 2;

}  // namespace

Replayer::Replayer(const TracedRay& ray, int checkpoint_every)
    : ray_(&ray), every_(std::max(checkpoint_every, 1)) {
  const std::vector<Event>& ev = ray.events;
  const int n = int(std::min<size_t>(ev.size(), size_t(std::numeric_limits<int>::max())));
  grows_.assign(size_t(n), 0);
  // One pass, as the kernel walked: the ray-wide lists, and what each event adds to them.
  std::unordered_map<int32_t, size_t> first_test;  // prim -> its first entry in tests_
  std::unordered_set<int32_t> left, skipped;
  std::vector<std::pair<uint32_t, int>> hits;  // (entry, event) of every mailbox hit
  Walk w;
  for (int i = 0; i < n; ++i) {
    if (i % every_ == 0) checkpoints_.push_back(w);
    const Event& e = ev[size_t(i)];
    switch (e.type) {
      case EventType::cell:
        cell_events_.push_back(i);
        break;
      case EventType::node:
      case EventType::pop:
        // The walk moves to another node (a leaf event names the node it is already at).
        if (w.node_event >= 0) {
          const int32_t from = ev[size_t(w.node_event)].node;
          if (!skipped.count(from) && left.insert(from).second) {
            left_.push_back(from);
            grows_[size_t(i)] |= kLeaves;
          }
        }
        break;
      case EventType::skip:  // BVH: the popped entry (the current node) is not visited
        if (skipped.insert(e.node).second) {
          skipped_.push_back(e.node);
          grows_[size_t(i)] |= kSkips;
        }
        break;
      case EventType::prim_test: {
        MailboxEntry m;
        m.prim = e.prim;
        m.tested_in_cell_event = w.cell_event;
        if (w.cell_event >= 0)
          std::copy(ev[size_t(w.cell_event)].cell, ev[size_t(w.cell_event)].cell + 3, m.cell);
        if (w.node_event >= 0) m.leaf = ev[size_t(w.node_event)].node;
        m.hit = e.hit;
        m.t = e.t;
        first_test.emplace(e.prim, tests_.size());
        tests_.push_back(m);
        break;
      }
      case EventType::mailbox_hit:
        if (auto it = first_test.find(e.prim); it != first_test.end())
          hits.emplace_back(uint32_t(it->second), i);
        break;
      default:
        break;
    }
    advance(w, i);
  }
  // The mailbox hits grouped by entry, each group in event order (a counting sort, stable).
  hit_start_.assign(tests_.size() + 1, 0);
  for (const auto& h : hits) ++hit_start_[h.first + 1];
  for (size_t j = 0; j < tests_.size(); ++j) hit_start_[j + 1] += hit_start_[j];
  hits_.resize(hits.size());
  std::vector<uint32_t> fill(hit_start_.begin(), hit_start_.end() - 1);
  for (const auto& h : hits) hits_[fill[h.first]++] = h.second;
}

// One event, as the kernel did it, on the walk's small state.
void Replayer::advance(Walk& w, int i) const {
  const Event& e = ray_->events[size_t(i)];
  w.nearest_prim_before = w.nearest_prim;
  switch (e.type) {
    case EventType::cell:
      w.cell_event = i;
      w.has_interval = true;
      w.t_min = e.t_enter;
      w.t_max = e.t_exit;
      ++w.counters.cells;
      break;
    case EventType::node:
    case EventType::pop:
    case EventType::leaf:
      if (grows_[size_t(i)] & kLeaves) ++w.left;
      w.node_event = i;
      w.has_interval = true;
      w.t_min = e.t_min_node;
      w.t_max = e.t_max_node;
      if (e.type == EventType::node) ++w.counters.nodes;
      if (e.type == EventType::pop) {
        ++w.counters.pops;
        if (!w.stack.empty()) w.stack.pop_back();
      }
      break;
    case EventType::box_test:  // BVH: a child's box tested; the inner node stays the current one
      ++w.counters.box_tests;
      break;
    case EventType::skip:
      if (grows_[size_t(i)] & kSkips) ++w.skipped;
      break;
    case EventType::push:  // the far child waits on the stack; the inner node stays the current one
      ++w.counters.pushes;
      w.stack.push_back(StackEntry{e.node, e.depth, e.t_min_node, e.t_max_node, i});
      break;
    case EventType::prim_test:
      ++w.counters.prim_tests;
      if (e.hit) {
        ++w.counters.prim_hits;
        // A tie (the same t) goes to the lower primitive id, as in the kernels.
        const bool lost_tie = w.nearest_prim >= 0 && e.t == w.nearest_t && e.prim > w.nearest_prim;
        if (!lost_tie) {
          w.nearest_prim = e.prim;
          w.nearest_t = e.t;
          w.deferred = false;
        }
      }
      break;
    case EventType::mailbox_hit:
      ++w.counters.mailbox_hits;
      break;
    case EventType::hit_deferred:
      w.deferred = true;
      break;
    case EventType::hit_accepted:
      w.accepted = true;
      w.deferred = false;
      w.reason = e.reason;
      w.nearest_prim = e.prim;
      w.nearest_t = e.t;
      break;
    case EventType::ray_end:
      w.ended = true;
      break;
    default:
      break;
  }
}

int Replayer::skips(size_t entry, int step) const {
  auto first = hits_.begin() + hit_start_[entry], last = hits_.begin() + hit_start_[entry + 1];
  return int(std::upper_bound(first, last, step) - first);
}

ReplayState Replayer::at(int step) const {
  ReplayState s;
  const std::vector<Event>& ev = ray_->events;
  if (grows_.empty()) return s;
  step = std::clamp(step, 0, int(grows_.size()) - 1);
  s.step = step;
  s.event = &ev[size_t(step)];

  // From the checkpoint at or before the step, the events up to it.
  Walk w = checkpoints_[size_t(step / every_)];
  for (int i = step / every_ * every_; i <= step; ++i) advance(w, i);

  s.cell_event = w.cell_event;
  if (w.counters.cells > 1)
    s.visited_cell_events.assign(cell_events_.begin(), cell_events_.begin() + (w.counters.cells - 1));
  s.node_event = w.node_event;
  s.stack = std::move(w.stack);
  s.visited_nodes.assign(left_.begin(), left_.begin() + w.left);
  s.skipped_nodes.assign(skipped_.begin(), skipped_.begin() + w.skipped);
  s.mailbox.assign(tests_.begin(), tests_.begin() + w.counters.prim_tests);
  for (size_t j = 0; j < s.mailbox.size(); ++j)
    if (hit_start_[j + 1] != hit_start_[j]) s.mailbox[j].skips = skips(j, step);
  s.counters = w.counters;
  s.nearest_prim = w.nearest_prim;
  s.nearest_t = w.nearest_t;
  s.nearest_prim_before = w.nearest_prim_before;
  s.deferred = w.deferred;
  s.accepted = w.accepted;
  s.ended = w.ended;
  s.reason = w.reason;
  s.has_interval = w.has_interval;
  s.t_min = w.t_min;
  s.t_max = w.t_max;

  // The primitives of the current cell (or leaf): the tests and mailbox hits between it and the next one.
  const int block_start = std::max(s.cell_event, s.node_event);
  s.block_event = block_start;
  if (block_start >= 0) {
    for (size_t i = size_t(block_start) + 1; i < ev.size(); ++i) {
      const Event& e = ev[i];
      if (e.type == EventType::cell || is_tree_event(e.type) || e.type == EventType::ray_end) break;
      if (e.type != EventType::prim_test && e.type != EventType::mailbox_hit) continue;
      PrimMark p;
      p.prim = e.prim;
      if (int(i) > step)
        p.state = PrimState::pending;
      else if (e.type == EventType::mailbox_hit)
        p.state = PrimState::skipped;
      else if (int(i) == step)
        p.state = PrimState::testing;
      else
        p.state = e.hit ? PrimState::hit : PrimState::missed;
      p.t = e.t;
      p.hit = e.type == EventType::prim_test && e.hit;
      s.prims.push_back(p);
    }
  }
  return s;
}

}  // namespace raystep::replay
