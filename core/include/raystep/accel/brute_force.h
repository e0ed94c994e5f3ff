// Vanilla ray tracing: test every primitive (cost n per ray). The reference every structure must agree with.
#pragma once

#include "raystep/accel/accelerator.h"

namespace raystep {

class BruteForce final : public Accelerator {
 public:
  std::string name() const override { return "brute"; }
  void build(const Geometry& geometry) override { geometry_ = &geometry; }
  bool intersect(const Ray& ray, Hit* hit) const override;
  bool occluded(const Ray& ray) const override;
  bool intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const override;
  bool occluded_counted(const Ray& ray, CountingRecorder& counters) const override;
  size_t memory_bytes() const override { return 0; }  // nothing but the geometry

 private:
  const Geometry* geometry_ = nullptr;
};

}  // namespace raystep
