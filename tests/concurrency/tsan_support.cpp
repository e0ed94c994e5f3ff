// What a ThreadSanitizer test executable needs to see TBB's synchronisation (built only with RAYSTEP_TSAN):
// libtbb told to load the ITT bridge (tsan_itt_bridge.c) before the first parallel call, so that running the
// executable by hand needs no environment; and TBB's small-object pool. A task object freed on one thread
// goes back to its owner's pool (through atomics inside libtbb) and is reused there for the next task; malloc
// and free would tell TSan that the old object's accesses happen before the new one's, the pool does not. So
// this file stands in front of libtbb's allocate (the executable's definition wins over the library's) and
// acquires what the destruction released (__itt_sync_destroy in the bridge).
#include <dlfcn.h>
#include <sanitizer/tsan_interface.h>

#include <cstddef>
#include <cstdlib>

#include <oneapi/tbb/detail/_small_object_pool.h>
#include <oneapi/tbb/detail/_task.h>

namespace {

// Before main, hence before TBB starts (it reads the variables once, at its first parallel call). A variable
// already set is kept: the bridge can be swapped for a real ITT collector by hand.
const bool itt_bridge_named = [] {
  setenv("INTEL_LIBITTNOTIFY64", RAYSTEP_TSAN_ITT_LIBRARY, 0);
  setenv("INTEL_ITTNOTIFY_GROUPS", "sync", 0);
  return true;
}();

}  // namespace

// The suppressions (tsan.supp here: each with its reason) without a TSAN_OPTIONS to remember.
extern "C" const char* __tsan_default_options() {
  return "suppressions=" RAYSTEP_TSAN_SUPPRESSIONS " second_deadlock_stack=1";
}

namespace tbb {
namespace detail {
namespace r1 {

namespace {
template <typename Fn>
Fn next_definition(const char* mangled) {
  void* f = dlsym(RTLD_NEXT, mangled);
  if (!f) std::abort();  // not libtbb 2021's interface: fail loudly rather than hide races
  return reinterpret_cast<Fn>(f);
}
}  // namespace

// A wait returns when the last task has dropped the wait_context's reference count to zero: each task's
// fetch_sub releases the count, and the library's wait loop (inside libtbb, uninstrumented) acquires it. The
// header's ITT notice after the wait names the object, not the count, and the tasks' notices come before
// their fetch_sub; so the acquire the library did is done again here, on the count itself (the second word of
// wait_context: m_version_and_traits, then the atomic m_ref_count). Without it a task's last decrement looks
// like a race with whatever later reuses that memory (the waiting frame's stack).
namespace {
constexpr std::size_t kRefCountOffset = sizeof(std::uint64_t);
static_assert(sizeof(d1::wait_context) == 2 * sizeof(std::uint64_t), "not libtbb 2021's wait_context");
void acquire_ref_count(d1::wait_context& w) {
  __tsan_acquire(reinterpret_cast<char*>(&w) + kRefCountOffset);
}
}  // namespace

void wait(d1::wait_context& w, d1::task_group_context& ctx) {
  using Fn = void (*)(d1::wait_context&, d1::task_group_context&);
  static const Fn real =
      next_definition<Fn>("_ZN3tbb6detail2r14waitERNS0_2d112wait_contextERNS2_18task_group_contextE");
  real(w, ctx);
  acquire_ref_count(w);
}

void execute_and_wait(d1::task& t, d1::task_group_context& t_ctx, d1::wait_context& w,
                      d1::task_group_context& w_ctx) {
  using Fn = void (*)(d1::task&, d1::task_group_context&, d1::wait_context&, d1::task_group_context&);
  static const Fn real = next_definition<Fn>(
      "_ZN3tbb6detail2r116execute_and_waitERNS0_2d14taskERNS2_18task_group_contextERNS2_12wait_contextES6_");
  real(t, t_ctx, w, w_ctx);
  acquire_ref_count(w);
}

void* allocate(d1::small_object_pool*& pool, std::size_t bytes, const d1::execution_data& ed) {
  using Fn = void* (*)(d1::small_object_pool*&, std::size_t, const d1::execution_data&);
  static const Fn real =
      next_definition<Fn>("_ZN3tbb6detail2r18allocateERPNS0_2d117small_object_poolEmRKNS2_14execution_dataE");
  void* p = real(pool, bytes, ed);
  __tsan_acquire(p);
  return p;
}

void* allocate(d1::small_object_pool*& pool, std::size_t bytes) {
  using Fn = void* (*)(d1::small_object_pool*&, std::size_t);
  static const Fn real = next_definition<Fn>("_ZN3tbb6detail2r18allocateERPNS0_2d117small_object_poolEm");
  void* p = real(pool, bytes);
  __tsan_acquire(p);
  return p;
}

}  // namespace r1
}  // namespace detail
}  // namespace tbb
