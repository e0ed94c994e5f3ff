// A structure answered by one walk (lecture: "instrumentation that costs nothing when off"): the accelerator
// interface's four queries are the structure's kernel traverse<Recorder>(ray, hit, any_hit, rec) with the
// null recorder or the counting one, so a structure writes only its build and its walk. CRTP, not a virtual:
// the kernel is called directly, and the null recorder's walk is the kernel alone.
#pragma once

#include "raystep/accel/accelerator.h"
#include "raystep/record/recorder.h"

namespace raystep {

// Derived has `template <class Recorder> bool traverse(const Ray&, Hit*, bool any_hit, Recorder&) const`,
// built over a Geometry with Options.
template <class Derived, class Options>
class RecordedWalk : public Accelerator {
 public:
  // Out of line, as when each structure defined them in its .cpp: a caller's loop on a concrete structure
  // does not absorb the kernel, so the instructions bench/README.md counts stay those of the kernel.
  [[gnu::noinline]] bool intersect(const Ray& ray, Hit* hit) const override {
    NullRecorder rec;
    return walk().traverse(ray, hit, false, rec);
  }
  [[gnu::noinline]] bool occluded(const Ray& ray) const override {
    NullRecorder rec;
    Hit hit;
    return walk().traverse(ray, &hit, true, rec);
  }
  bool intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const override {
    return walk().traverse(ray, hit, false, counters);
  }
  bool occluded_counted(const Ray& ray, CountingRecorder& counters) const override {
    Hit hit;
    return walk().traverse(ray, &hit, true, counters);
  }

  const Options& options() const { return options_; }
  const Geometry& geometry() const { return *geometry_; }

 protected:
  explicit RecordedWalk(Options options) : options_(options) {}

  Options options_;
  const Geometry* geometry_ = nullptr;  // set by build()

 private:
  const Derived& walk() const { return static_cast<const Derived&>(*this); }
};

}  // namespace raystep
