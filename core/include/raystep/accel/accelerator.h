// The accelerator interface: every structure (brute force, bounding volumes, grid, kd-tree, BVH) answers
// the same two queries on the same primitive ids, so each can be checked against brute force.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "raystep/geometry/ray.h"
#include "raystep/scene/geometry.h"
#include "raystep/record/recorder.h"

namespace raystep {

class Accelerator {
 public:
  virtual ~Accelerator() = default;
  virtual std::string name() const = 0;
  // Build over the geometry, which must outlive the accelerator.
  virtual void build(const Geometry& geometry) = 0;
  // Nearest hit with ray.tmin < t < ray.tmax; false (and hit->prim = -1) on a miss.
  virtual bool intersect(const Ray& ray, Hit* hit) const = 0;
  // Any hit with ray.tmin < t < ray.tmax (shadow rays).
  virtual bool occluded(const Ray& ray) const = 0;
  // intersect(), counting its work (cells or nodes visited, primitive tests, mailbox hits): heat maps.
  virtual bool intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const = 0;
  // occluded(), counting its work: the cost report counts the shadow rays' tests too. The default counts a
  // nearest-hit query, which tests at least as many primitives as an any-hit query.
  virtual bool occluded_counted(const Ray& ray, CountingRecorder& counters) const {
    Hit hit;
    return intersect_counted(ray, &hit, counters);
  }
  // The bytes the built structure allocated (its arrays' capacities), not counting the geometry it refers to
  // nor the per-thread mailbox stamps (4 bytes per primitive per thread). `raystep compare` reports it.
  virtual size_t memory_bytes() const { return 0; }
};

// The names accepted by make_accelerator, for --help texts.
std::vector<std::string> accelerator_names();
// The structures whose walks are recorded (every name but brute force and the bounding-volume kinds), as
// text for messages: "grid, kd, ..., octree or bsp"; trees_only: without the grid.
std::string recorded_structure_list(bool trees_only = false);
// With default build options (accel/structure_options.h has the overload that takes options).
// Throws InputError("", 0, "unknown accelerator ...") for an unknown name.
std::unique_ptr<Accelerator> make_accelerator(const std::string& name);

}  // namespace raystep
