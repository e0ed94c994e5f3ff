/* TBB's hand-offs as ThreadSanitizer sees them. Debian's libtbb is not built with TSan, so the scheduler's
 * own atomics (a task spawned on one thread and run on another, a wait that returns when the last task ends)
 * are invisible to it, and every parallel_for would look like a data race. TBB reports exactly these points
 * to Intel's threading tools through ITT (sync_releasing before a hand-off, sync_acquired after it): the
 * library itself (task pools, mailboxes, steals) and, with TBB_USE_PROFILING_TOOLS=2, the headers (spawn,
 * wait, the reduction tree). libtbb loads this file as its ITT collector (INTEL_LIBITTNOTIFY64 = this
 * library, INTEL_ITTNOTIFY_GROUPS = sync; ctest sets both), and each notification becomes the TSan annotation
 * of the same meaning. Only TBB's own synchronisation is added: two task bodies that touch the same memory
 * without synchronising are still reported (the canary tests check it). */
#include <sanitizer/tsan_interface.h>

/* Its presence makes the loader take this library as a version-1 collector: every __itt_* function below
 * is looked up by name, the others stay no-ops. */
void __itt_api_version(void) {}

void __itt_sync_releasing(void* addr) {
  __tsan_release(addr);
}
void __itt_sync_acquired(void* addr) {
  __tsan_acquire(addr);
}
/* A task's memory goes back to TBB's pool: what was done to it happens before its reuse (the allocation
 * side acquires it: tsan_tbb_pool.cpp). */
void __itt_sync_destroy(void* addr) {
  __tsan_release(addr);
}
