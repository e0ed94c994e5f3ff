// Mailboxes (Amanatides and Woo 1987; Kirk and Arvo): a primitive referenced by several cells or leaves is
// tested once per ray. Each ray gets an increasing number; each primitive remembers the number of the last
// ray tested against it; a match means "already tested, skip". The stamps live per thread (and per
// structure), so parallel rendering needs no locks and a const structure can be shared by all threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

namespace raystep {

// The stamps of one thread for one structure, valid during one ray.
class MailboxStamp {
 public:
  MailboxStamp(uint32_t ray, uint32_t* stamps) : ray_(ray), stamps_(stamps) {}
  // True the first time the primitive is seen by this ray (and marks it); false afterwards.
  bool first_visit(uint32_t prim) {
    if (stamps_[prim] == ray_) return false;
    stamps_[prim] = ray_;
    return true;
  }

 private:
  uint32_t ray_;
  uint32_t* stamps_;
};

class Mailboxes {
 public:
  // Called by a structure's build: a fresh identity, so stale per-thread stamps are never reused.
  void reset(size_t prim_count) {
    prim_count_ = prim_count;
    static std::atomic<uint64_t> next_owner{1};
    owner_ = next_owner.fetch_add(1);
  }

  MailboxStamp begin_ray() const {
    Slot& s = slot();
    if (++s.ray == 0) {  // ray numbers wrapped around: forget every stamp
      std::fill(s.stamps.begin(), s.stamps.end(), 0u);
      s.ray = 1;
    }
    return MailboxStamp(s.ray, s.stamps.data());
  }

 private:
  struct Slot {
    uint64_t owner = 0;
    uint32_t ray = 0;
    std::vector<uint32_t> stamps;
  };
  // A thread keeps stamps for a few structures at once (e.g. a test comparing two grids ray by ray).
  Slot& slot() const {
    thread_local Slot slots[4];
    thread_local unsigned next_victim = 0;
    for (Slot& s : slots)
      if (s.owner == owner_) return s;
    Slot& s = slots[next_victim++ % 4];
    s.owner = owner_;
    s.ray = 0;
    s.stamps.assign(prim_count_, 0u);
    return s;
  }

  size_t prim_count_ = 0;
  uint64_t owner_ = 0;
};

}  // namespace raystep
