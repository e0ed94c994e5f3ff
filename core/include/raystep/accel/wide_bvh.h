// The wide BVH: the binary BVH collapsed into nodes of up to 4 or 8 children by SAH, the children's boxes
// stored as structure of arrays and tested together with SIMD (SSE everywhere on x86-64, AVX2 chosen at run
// time where the CPU has it, a scalar path elsewhere), children visited nearest first, triangles laid out for
// the kernel. The same watertight triangle test as every structure: the same hits, bit for bit, as the
// binary BVH. The fast structure; the binary one (bvh.h) is the lecture's.
#pragma once

#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bvh_build.h"
#include "raystep/record/recorder.h"

namespace raystep {

class EventRecorder;

// The wide tree as traces and the debugger see it: every child slot of every wide node has an id (ids in
// depth-first preorder, the root 0). An inner node lists its children's ids, a leaf its primitive ids.
struct WideBvhView {
  struct Node {
    Bounds3 box;
    int32_t parent = -1;
    int32_t depth = 0;
    bool leaf = false;
    std::vector<int32_t> children;  // inner nodes: up to width ids
    std::vector<uint32_t> prims;    // leaves
  };
  std::vector<Node> nodes;
};

// The kernels WideBvh can run; simd_level() names the one in use.
enum class WideSimd : uint8_t { scalar, sse, avx2 };

class WideBvh final : public Accelerator {
 public:
  // width 4 or 8; the binary tree is built with `options` first.
  explicit WideBvh(int width = 8, BvhOptions options = {});
  ~WideBvh() override;
  WideBvh(const WideBvh&) = delete;
  WideBvh& operator=(const WideBvh&) = delete;
  std::string name() const override;  // "bvh4" or "bvh8"
  void build(const Geometry& geometry) override;
  // Collapse a binary hierarchy already built over `geometry` (tests, and the binary BVH's own tree).
  void build(const Geometry& geometry, const BvhData& binary);
  bool intersect(const Ray& ray, Hit* hit) const override;
  bool occluded(const Ray& ray) const override;
  bool intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const override;
  bool occluded_counted(const Ray& ray, CountingRecorder& counters) const override;
  size_t memory_bytes() const override;
  // "avx2", "sse" or "scalar": the kernel this machine runs (or the one forced by force_simd).
  static const char* simd_level();
  // The best level this CPU can run.
  static WideSimd best_simd();
  // Tests: run every WideBvh with `level` (false, and no change, if this CPU cannot run it).
  static bool force_simd(WideSimd level);

  // The traversal kernel, instrumented through the recorder (record/recorder.h): node, box_test (one per
  // non-empty child slot), push (in the order chosen: the farthest first), pop, skip, leaf, prim_test,
  // hit_accepted, ray_end. Ties at equal t go to the lower primitive id, as in brute force. Instantiated for
  // NullRecorder, CountingRecorder and EventRecorder.
  template <class Recorder>
  bool traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const;
  // The recorded walk for traces (node ids as in describe()).
  bool record(const Ray& ray, Hit* hit, bool any_hit, EventRecorder& rec) const;
  WideBvhView describe() const;
  // One node of describe() (throws InputError for an id it has not), in time independent of the tree's
  // size: what a trace of a few rays needs of a big tree.
  WideBvhView::Node describe_node(int32_t id) const;
  size_t node_count() const;  // describe().nodes.size()
  size_t leaf_count() const;

  int width() const { return width_; }
  const BvhOptions& options() const { return options_; }

  struct Impl;

 private:
  int width_;
  BvhOptions options_;
  Impl* impl_ = nullptr;  // the wide nodes and the triangle layout (wide_bvh.cpp and its kernels)
};

}  // namespace raystep
