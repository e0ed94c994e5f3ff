// The wide BVH: the binary BVH collapsed into nodes of up to 4 or 8 children by SAH, the children's boxes
// stored as structure of arrays and tested together with SIMD (SSE everywhere on x86-64, AVX2 chosen at run
// time where the CPU has it, a scalar path elsewhere), children visited nearest first, triangles laid out for
// the kernel. The same watertight triangle test as every structure: the same hits, bit for bit, as the
// binary BVH. The fast structure; the binary one (bvh.h) is the lecture's.
#pragma once

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bvh_build.h"
#include "raystep/trace/recorder.h"

namespace raystep {

class WideBvh final : public Accelerator {
 public:
  // width 4 or 8; the binary tree is built with `options` first.
  explicit WideBvh(int width = 8, BvhOptions options = {});
  ~WideBvh() override;
  std::string name() const override;  // "bvh4" or "bvh8"
  void build(const Geometry& geometry) override;
  bool intersect(const Ray& ray, Hit* hit) const override;
  bool occluded(const Ray& ray) const override;
  bool intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const override;
  bool occluded_counted(const Ray& ray, CountingRecorder& counters) const override;
  size_t memory_bytes() const override;
  // "avx2", "sse" or "scalar": the kernel this machine runs.
  static const char* simd_level();

  int width() const { return width_; }
  const BvhOptions& options() const { return options_; }

 private:
  int width_;
  BvhOptions options_;
  struct Impl;
  Impl* impl_ = nullptr;  // the wide nodes and the triangle layout (wide_bvh.cpp and its kernels)
};

}  // namespace raystep
