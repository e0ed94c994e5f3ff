// Whole-build logging: the kd-tree builder's events (every candidate plane of every node, each split, each leaf)
// as trace build events. BuildEventWriter writes each one to a stream as the builder makes it, as the entries of
// a trace's "build" array (docs/trace-format.md): nothing is kept, memory stays flat however large the build.
// BuildEventCollector keeps them, for small builds shown whole (tests, the debugger).
#pragma once

#include <ostream>
#include <vector>

#include "raystep/accel/kdtree_build.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

// Turns the listener's calls into TraceBuildEvents and hands each to add().
class BuildEventListener : public BuildListener {
 public:
  bool wants_candidates(uint32_t) const override { return true; }
  void sah_candidate(uint32_t node, const SahCandidate& c) override;
  void split(uint32_t node, const KdNodeInfo& info, uint32_t n_prims, int axis, float position, float cost,
             float leaf_cost) override;
  void leaf_made(uint32_t node, const KdNodeInfo& info, uint32_t n_prims, float leaf_cost,
                 LeafReason reason) override;

 protected:
  virtual void add(const TraceBuildEvent& event) = 0;
};

class BuildEventWriter final : public BuildEventListener {
 public:
  explicit BuildEventWriter(std::ostream& out) : out_(out) {}
  size_t count() const { return count_; }

 private:
  void add(const TraceBuildEvent& event) override;
  std::ostream& out_;
  size_t count_ = 0;
};

class BuildEventCollector final : public BuildEventListener {
 public:
  std::vector<TraceBuildEvent> events;

 private:
  void add(const TraceBuildEvent& event) override { events.push_back(event); }
};

}  // namespace raystep
