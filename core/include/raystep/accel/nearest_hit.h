// The nearest hit of one ray so far, and the primitive test that every structure's cells and leaves share:
// skip a primitive the ray's mailbox has already seen, test it up to just above the nearest hit (so that a
// tie is seen), and keep it when nearer. A tie at the same t (coincident faces, a shared edge) goes to the
// lower primitive id, as in brute force, so every structure reports the same hit.
#pragma once

#include <cstdint>

#include "raystep/accel/mailbox.h"
#include "raystep/geometry/numerics.h"
#include "raystep/scene/geometry.h"

namespace raystep {

struct NearestHit {
  Hit hit;
  float t;        // the nearest hit's t, or the ray's tmax while there is none
  float t_limit;  // the primitive tests' bound: once there is a hit, just above it, so that ties are seen

  explicit NearestHit(float ray_tmax) : t(ray_tmax), t_limit(ray_tmax) {}
  bool found() const { return hit.found(); }

  // Tests `prim` unless the mailbox (null: no mailboxes) says this ray has tested it. True when it became the
  // nearest hit. Inlined by force, and the triangle test with it (Geometry::intersect<true>): left to itself
  // the compiler called the triangle test out of line from the grid's walk, 4.6% more instructions than the
  // hook-free copy (0.6% with it inline; 16,384 bunny rays under callgrind). The kd-tree keeps its own copy
  // of this loop: with this one its triangle test is not inlined either way (+2-3% instructions per ray).
  template <class Recorder>
  [[gnu::always_inline]] bool test(const Geometry& geometry, uint32_t prim, const Ray& ray,
                                   const WatertightRay& wray, MailboxStamp* mailbox, Recorder& rec) {
    if (mailbox && !mailbox->first_visit(prim)) {
      rec.mailbox_hit(prim);
      return false;
    }
    Hit candidate;
    bool found = geometry.template intersect<true>(prim, ray, wray, t_limit, &candidate);
    rec.prim_test(prim, found, candidate.t);
    if (!found || (candidate.t == t && int32_t(prim) > hit.prim)) return false;
    hit = candidate;
    t = candidate.t;
    t_limit = next_float_up(t);
    return true;
  }
};

}  // namespace raystep
