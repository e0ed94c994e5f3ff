// Races planted on purpose, built only with RAYSTEP_TSAN: ctest expects ThreadSanitizer to report each one
// (PASS_REGULAR_EXPRESSION names the planted function). They show that the ITT bridge (tsan_itt_bridge.c,
// tsan_tbb_pool.cpp) adds only TBB's own hand-offs: two task bodies, or a worker and the GUI thread, that
// share memory without synchronising are still caught. The same mistakes in the shapes the core uses: a
// progress counter in a render's rows, a BVH node slot written by both subtrees, a cancel flag that is not
// atomic.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

namespace {

// Holds a task body until a body has also run on the arena's second thread (at most two seconds), so that the
// planted accesses surely come from two threads whatever the machine's load. seen: one per planted race. The
// planted accesses come a few sleeps later: an access right after this handshake would share its epoch with
// TSan's release of `seen`, and look ordered.
void wait_for_second_thread(std::atomic<int>& seen) {
  const int index = tbb::this_task_arena::current_thread_index();
  if (index >= 0 && index < 2) seen.fetch_or(1 << index);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (seen.load() != 3 && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

// noinline: the function keeps its name in the report's stacks, which ctest looks for.
__attribute__((noinline)) int planted_race_in_parallel_for() {
  int rows_done = 0;  // should be std::atomic<int>, as ProgressBar's counter is
  std::atomic<int> seen{0};
  tbb::task_arena arena(2);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, 64, 1), [&](const tbb::blocked_range<int>& rows) {
      wait_for_second_thread(seen);
      for (int k = 0; k < 3; ++k) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        rows_done += int(rows.size());
      }
    });
  });
  return rows_done;
}

__attribute__((noinline)) void planted_race_in_parallel_invoke(int depth, int* shared_slot,
                                                               std::atomic<int>& seen) {
  if (depth == 0) {
    wait_for_second_thread(seen);
    for (int k = 0; k < 3; ++k) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      *shared_slot += 1;  // both subtrees write the same slot
    }
    return;
  }
  tbb::parallel_invoke([&] { planted_race_in_parallel_invoke(depth - 1, shared_slot, seen); },
                       [&] { planted_race_in_parallel_invoke(depth - 1, shared_slot, seen); });
}

__attribute__((noinline)) int planted_race_on_cancel_flag() {
  bool cancel = false;  // should be std::atomic<bool>, as ReportWindow's cancel_ is
  int rows = 0;
  std::thread worker([&] {
    for (int i = 0; i < 50 && !cancel; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      ++rows;
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  cancel = true;  // the GUI thread's click
  worker.join();
  return rows;
}

TEST(TsanCanary, RaceInParallelFor) {
  EXPECT_LE(planted_race_in_parallel_for(), 3 * 64);  // racing updates may be lost
}

TEST(TsanCanary, RaceInParallelInvoke) {
  int slot = 0;
  tbb::task_arena arena(2);
  std::atomic<int> seen{0};
  arena.execute([&] { planted_race_in_parallel_invoke(4, &slot, seen); });
  EXPECT_GT(slot, 0);
}

TEST(TsanCanary, RaceOnCancelFlag) {
  EXPECT_GE(planted_race_on_cancel_flag(), 0);
}

}  // namespace
