// Whole-build logging with bounded memory: a BuildListener that writes each kd-tree build event (every candidate
// plane of every node, each split, each leaf) to a stream as the builder makes it, as the entries of a trace's
// "build" array (see docs/trace-format.md). Nothing is kept: memory stays flat however large the build.
#pragma once

#include <ostream>

#include "raystep/accel/kdtree_build.h"

namespace raystep {

class BuildEventWriter final : public BuildListener {
 public:
  explicit BuildEventWriter(std::ostream& out) : out_(out) {}
  bool wants_candidates(uint32_t) const override { return true; }
  void sah_candidate(uint32_t node, const SahCandidate& c) override;
  void split(uint32_t node, const KdNodeInfo& info, uint32_t n_prims, int axis, float position, float cost,
             float leaf_cost) override;
  void leaf_made(uint32_t node, const KdNodeInfo& info, uint32_t n_prims, float leaf_cost,
                 LeafReason reason) override;
  size_t count() const { return count_; }

 private:
  std::ostream& out_;
  size_t count_ = 0;
};

}  // namespace raystep
