// The core's threads exercised at once, as the debugger's workers use them: several renders of one shared
// structure, a build running beside a render and a heat map, a rebuild while a heat map still reads the old
// structure, SAH curves recorded while the user steps through a pixel's trace, the reports cancelled from
// another thread, and the progress bar's thread. Built alone with ThreadSanitizer by scripts/test.sh (the
// `concurrency` label, build-tsan); every test also checks its answer against the same work done alone.
#include <gtest/gtest.h>
#include <pty.h>
#include <unistd.h>

#include <atomic>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <tbb/global_control.h>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/accel/structure_options.h"
#include "raystep/render/render.h"
#include "raystep/report/aa_report.h"
#include "raystep/report/cost_report.h"
#include "raystep/report/grid_sweep.h"
#include "raystep/report/structure_compare.h"
#include "raystep/trace/heatmap.h"
#include "raystep/trace/record_trace.h"

namespace raystep {
namespace {

// TBB gives the whole process at most (cores - 1) worker threads: on a 2-core machine one worker, which
// several arenas at once would share, leaving most heat maps and builds on their calling thread alone. Four
// workers let every arena here run its tasks on two threads, as on the students' machines.
class EnoughWorkers : public ::testing::Environment {
 public:
  void SetUp() override {
    allow_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, 5);
  }
  void TearDown() override { allow_.reset(); }

 private:
  std::unique_ptr<tbb::global_control> allow_;
};
[[maybe_unused]] ::testing::Environment* const enough_workers =
    ::testing::AddGlobalTestEnvironment(new EnoughWorkers);

// The debugger's document, as viz/src/app/session.h holds it: the scene, and a structure built over it that
// keeps the scene alive. Workers receive both by shared pointer.
struct Built {
  std::shared_ptr<const Scene> scene;
  std::string kind;
  std::unique_ptr<Accelerator> accel;
};

// A floor, a mirror sphere and a glass sphere over a soup of 5000 small triangles: enough primitives for the
// BVH builder's parallel paths (subtrees as tasks, binning in parallel chunks from 4096 primitives up).
std::shared_ptr<const Scene> make_scene() {
  auto s = std::make_shared<Scene>();
  s->camera.eye = glm::vec3(0.f, 1.5f, 7.f);
  s->camera.look_at = glm::vec3(0.f, 0.5f, 0.f);
  s->camera.fov_deg = 45.f;
  s->render.ambient = glm::vec3(0.1f);
  s->render.background = glm::vec3(0.2f, 0.3f, 0.5f);
  s->render.width = 48;
  s->render.height = 36;
  Material matte, chrome, glass;
  matte.diffuse = glm::vec3(0.7f, 0.6f, 0.5f);
  chrome.diffuse = glm::vec3(0.1f);
  chrome.mirror = 0.7f;
  glass.diffuse = glm::vec3(0.f);
  glass.transparency = 0.9f;
  glass.ior = 1.5f;
  s->materials = {matte, chrome, glass};
  Geometry& g = s->geometry;
  g.begin_object("floor", 0);
  g.add_triangle({-5.f, -2.f, -5.f}, {-5.f, -2.f, 5.f}, {5.f, -2.f, 5.f});
  g.add_triangle({-5.f, -2.f, -5.f}, {5.f, -2.f, 5.f}, {5.f, -2.f, -5.f});
  g.begin_object("soup", 0);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-2.f, 2.f), d(-0.15f, 0.15f);
  for (int i = 0; i < 5000; ++i) {
    glm::vec3 p(u(rng), u(rng), u(rng) - 1.f);
    g.add_triangle(p, p + glm::vec3(d(rng), d(rng), d(rng)), p + glm::vec3(d(rng), d(rng), d(rng)));
  }
  g.begin_object("chrome", 1);
  g.add_sphere(Sphere{{-1.f, 0.5f, 1.5f}, 0.6f});
  g.begin_object("glass", 2);
  g.add_sphere(Sphere{{1.2f, 0.3f, 2.f}, 0.5f});
  Light key;
  key.position = glm::vec3(3.f, 6.f, 4.f);
  s->lights = {key};
  return s;
}

const std::shared_ptr<const Scene>& scene() {
  static const std::shared_ptr<const Scene> s = make_scene();
  return s;
}

std::shared_ptr<const Built> build(const std::string& kind, int bvh_threads = 2, int bins = 16) {
  auto b = std::make_shared<Built>();
  b->scene = scene();
  b->kind = kind;
  StructureOptions o;
  o.bvh.threads = bvh_threads;
  o.bvh.bins = bins;
  b->accel = make_accelerator(kind, o);
  b->accel->build(b->scene->geometry);
  return b;
}

RenderOptions render_opts(int threads) {
  RenderOptions o = render_options(scene()->render);
  o.aa.mode = AntiAliasing::Mode::jitter;
  o.aa.k = 2;
  o.threads = threads;
  return o;
}

bool same_image(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(a.pixels[0])) == 0;
}

bool same_bvh(const Bvh& a, const Bvh& b) {
  const BvhData &x = a.data(), &y = b.data();
  if (x.nodes.size() != y.nodes.size() || x.prim_index != y.prim_index) return false;
  for (size_t i = 0; i < x.nodes.size(); ++i)
    if (std::memcmp(&x.nodes[i], &y.nodes[i], sizeof(BvhNode)) != 0) return false;
  return true;
}

// The debugger's GUI thread in miniature: workers post closures (Qt's queued connections,
// ReportWindow::toGui), which the posting order runs on the thread that calls run_until_idle.
class GuiQueue {
 public:
  void post(std::function<void()> f) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      queue_.push_back(std::move(f));
    }
    wake_.notify_all();
  }
  // Runs what was posted until `done` holds (checked between closures and on every wake-up).
  void run_until(const std::function<bool()>& done) {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      while (!queue_.empty()) {
        auto f = std::move(queue_.front());
        queue_.pop_front();
        lock.unlock();
        f();
        lock.lock();
      }
      if (done()) return;
      wake_.wait(lock, [&] { return !queue_.empty(); });
    }
  }

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queue_;
};

// Three renders of one const structure at once, each itself parallel (TBB): the per-thread mailbox stamps of
// the grid and the kd-tree, the tracer's per-thread lists, and the images must not interfere.
TEST(Concurrency, SeveralRendersOfOneStructureAtOnce) {
  for (const char* kind : {"grid", "kd", "bvh", "bvh8"}) {
    auto s = build(kind);
    const RenderResult alone = render_image(*s->scene, *s->accel, render_opts(1));
    std::vector<RenderResult> results(3);
    std::vector<std::thread> workers;
    for (int i = 0; i < 3; ++i)
      workers.emplace_back(
          [&, i] { results[size_t(i)] = render_image(*s->scene, *s->accel, render_opts(2)); });
    for (auto& w : workers) w.join();
    for (const RenderResult& r : results) {
      EXPECT_TRUE(same_image(r.image, alone.image)) << kind;
      EXPECT_EQ(r.samples, alone.samples) << kind;
      EXPECT_EQ(r.rays.total(), alone.rays.total()) << kind;
    }
  }
}

// A render's progress bar is a thread of its own, drawn from a counter the render's threads advance; it runs
// only when stderr is a terminal, so stderr becomes a pseudo-terminal for one render. What the bar draws is
// passed on to the real stderr (a ThreadSanitizer report written meanwhile is not lost either).
TEST(Concurrency, ProgressBarBesideTheRender) {
  auto s = build("bvh", 2);
  RenderOptions o = render_opts(2);
  o.width = 96;
  o.height = 72;
  o.aa.k = 3;
  const RenderResult alone = render_image(*s->scene, *s->accel, o);

  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) GTEST_SKIP() << "no pseudo-terminal here";
  const int saved = dup(STDERR_FILENO);
  std::string drawn;
  std::thread drain([&] {
    char buf[512];
    for (ssize_t n; (n = read(master, buf, sizeof buf)) > 0;) {
      drawn.append(buf, size_t(n));
      if (write(saved, buf, size_t(n)) < 0) break;
    }
  });
  std::fflush(stderr);
  dup2(slave, STDERR_FILENO);
  o.progress = true;
  const RenderResult shown = render_image(*s->scene, *s->accel, o);
  std::fflush(stderr);
  dup2(saved, STDERR_FILENO);
  close(slave);  // the drain reads to the end, then gets EIO
  drain.join();
  close(master);
  close(saved);
  EXPECT_TRUE(same_image(shown.image, alone.image));
  // A bar drawn (the render took over half a second, as under ThreadSanitizer) ends erased.
  if (drawn.find('%') != std::string::npos) EXPECT_NE(drawn.find("\033[K"), std::string::npos);
}

// The debugger's build, render and heat map workers at once (main_window.cpp runTask): a render and a heat
// map of the current structure run while a rebuild with other options (the parallel BVH builder) is under
// way. The rebuild supersedes the render (a newer generation of "render" is asked for), so the stale picture
// is dropped on the GUI thread, as MainWindow drops it, and the new structure is rendered.
TEST(Concurrency, RebuildWhileRenderingAndMappingHeat) {
  auto current = build("bvh", 2, 16);
  const HeatMap heat_alone =
      compute_heatmap(current->scene->camera, *current->accel, 48, 36, HeatQuantity::boxes, 1);

  GuiQueue gui;
  int render_generation = 0, finished = 0;
  std::shared_ptr<const Built> shown_structure;
  std::unique_ptr<RenderResult> shown_picture;
  std::shared_ptr<const HeatMap> shown_heat;
  int dropped = 0;

  // What MainWindow::runTask does: the work on a worker, its result handed back to the GUI thread, where a
  // newer request of the same kind makes it stale.
  std::vector<std::thread> workers;
  auto run_render = [&](std::shared_ptr<const Built> s) {
    const int gen = ++render_generation;
    workers.emplace_back([&, s, gen] {
      auto r = std::make_shared<RenderResult>(render_image(*s->scene, *s->accel, render_opts(2)));
      gui.post([&, s, gen, r] {
        ++finished;
        if (gen != render_generation || s != current) {
          ++dropped;
          return;
        }
        shown_structure = s;
        shown_picture = std::make_unique<RenderResult>(*r);
      });
    });
  };
  run_render(current);
  workers.emplace_back([&, s = current] {
    auto h = std::make_shared<const HeatMap>(
        compute_heatmap(s->scene->camera, *s->accel, 48, 36, HeatQuantity::boxes, 2));
    gui.post([&, h] {
      ++finished;
      shown_heat = h;
    });
  });
  workers.emplace_back([&] {
    auto rebuilt = build("bvh", 2, 8);  // other options: another tree
    gui.post([&, rebuilt] {
      ++finished;
      current = rebuilt;  // the old structure lives on in the workers that hold it
      run_render(current);
    });
  });
  gui.run_until([&] { return finished == 4; });
  for (auto& w : workers) w.join();

  EXPECT_EQ(render_generation, 2);
  ASSERT_TRUE(shown_picture);
  EXPECT_EQ(shown_structure, current);
  EXPECT_TRUE(
      same_image(shown_picture->image, render_image(*current->scene, *current->accel, render_opts(1)).image));
  EXPECT_LE(dropped, 1);
  ASSERT_TRUE(shown_heat);
  EXPECT_EQ(shown_heat->values, heat_alone.values);
}

// Rebuilds while heat maps run: each heat map holds the structure it was asked for by shared pointer, while
// the "session" lets it go and builds the next; every map equals the one computed alone.
TEST(Concurrency, RebuildWhileHeatMapRuns) {
  std::vector<std::shared_ptr<const Built>> structures = {build("kd"), build("bvh", 2), build("octree")};
  std::vector<HeatMap> alone;
  for (const auto& s : structures)
    alone.push_back(compute_heatmap(s->scene->camera, *s->accel, 40, 30, HeatQuantity::cells, 1));

  std::shared_ptr<const Built> session = structures[0];
  std::vector<HeatMap> maps(structures.size());
  std::vector<std::thread> workers;
  for (size_t i = 0; i < structures.size(); ++i) {
    workers.emplace_back([&maps, i, s = session] {
      maps[i] = compute_heatmap(s->scene->camera, *s->accel, 40, 30, HeatQuantity::cells, 2);
    });
    structures[i].reset();  // the session's own reference goes: the worker's keeps it alive
    session = i + 1 < structures.size() ? structures[i + 1] : build("bvh-sweep", 2);
  }
  for (auto& w : workers) w.join();
  for (size_t i = 0; i < maps.size(); ++i) EXPECT_EQ(maps[i].values, alone[i].values) << i;
}

// Parallel BVH builds at once (each in its own TBB arena, subtrees as tasks and bins in parallel chunks),
// next to a kd-tree build: the same trees as built on one thread.
TEST(Concurrency, ParallelBuildsAtOnce) {
  auto one_thread = build("bvh", 1);
  auto sweep_alone = build("bvh-sweep", 1);
  std::vector<std::shared_ptr<const Built>> built(4);
  std::vector<std::thread> workers;
  workers.emplace_back([&] { built[0] = build("bvh", 2); });
  workers.emplace_back([&] { built[1] = build("bvh", 3); });
  workers.emplace_back([&] { built[2] = build("bvh-sweep", 2); });
  workers.emplace_back([&] { built[3] = build("kd"); });
  for (auto& w : workers) w.join();
  const Bvh& reference = dynamic_cast<const Bvh&>(*one_thread->accel);
  EXPECT_TRUE(same_bvh(dynamic_cast<const Bvh&>(*built[0]->accel), reference));
  EXPECT_TRUE(same_bvh(dynamic_cast<const Bvh&>(*built[1]->accel), reference));
  EXPECT_TRUE(
      same_bvh(dynamic_cast<const Bvh&>(*built[2]->accel), dynamic_cast<const Bvh&>(*sweep_alone->accel)));
  EXPECT_GT(dynamic_cast<const KdTree&>(*built[3]->accel).data().nodes.size(), 1u);
}

// The SAH inspector records a node's curve on a worker (the builder run again with a listener) while the
// user steps: pixel traces recorded through the same structures on the GUI thread.
TEST(Concurrency, SahCurvesWhileStepping) {
  auto kd = build("kd");
  auto bvh = build("bvh", 2);
  const KdOptions kd_options = dynamic_cast<const KdTree&>(*kd->accel).options();
  const BvhOptions bvh_options = dynamic_cast<const Bvh&>(*bvh->accel).options();
  const SahCurve kd_alone = record_sah_curve(scene()->geometry, kd_options, 1);
  const BvhSahCurve bvh_alone = record_bvh_sah_curve(scene()->geometry, bvh_options, 0);

  SahCurve kd_curve;
  BvhSahCurve bvh_curve;
  std::thread a([&] { kd_curve = record_sah_curve(scene()->geometry, kd_options, 1); });
  std::thread b([&] { bvh_curve = record_bvh_sah_curve(scene()->geometry, bvh_options, 0); });
  AntiAliasing none;
  size_t events = 0;
  for (int px = 20; px < 28; ++px)
    for (const auto* s : {kd.get(), bvh.get()}) {
      Trace t = record_pixel_trace(*s->scene, *s->accel, 48, 36, px, 18, none, 0, true, "", "");
      for (const TracedRay& r : t.rays) events += r.events.size();
    }
  a.join();
  b.join();
  EXPECT_GT(events, 0u);
  ASSERT_EQ(kd_curve.candidates.size(), kd_alone.candidates.size());
  for (size_t i = 0; i < kd_curve.candidates.size(); ++i)
    EXPECT_EQ(kd_curve.candidates[i].cost, kd_alone.candidates[i].cost);
  EXPECT_EQ(kd_curve.chosen, kd_alone.chosen);
  ASSERT_EQ(bvh_curve.candidates.size(), bvh_alone.candidates.size());
  for (size_t i = 0; i < bvh_curve.candidates.size(); ++i)
    EXPECT_EQ(bvh_curve.candidates[i].cost, bvh_alone.candidates[i].cost);
  EXPECT_EQ(bvh_curve.chosen, bvh_alone.chosen);
}

// A report on a worker, as ReportWindow runs one: rows and progress go to the GUI thread through the queue,
// Cancel is clicked on the GUI thread right after the first row arrives (the worker waits for the click, so
// that the test does not depend on timing), and the report returns the rows it finished.
struct CancelledRun {
  size_t rows_on_gui = 0;        // rows the GUI thread received
  size_t rows_returned = 0;      // rows in the returned report
  std::vector<double> progress;  // as the GUI thread saw it
  bool worker_done = false;
};

template <typename Run>
CancelledRun run_and_cancel_after_first_row(Run run) {
  GuiQueue gui;
  std::atomic<bool> cancel{false};
  std::mutex m;
  std::condition_variable clicked;
  bool click_seen = false;
  CancelledRun out;
  auto row_done = [&] {  // on the worker
    gui.post([&] {
      ++out.rows_on_gui;
      if (out.rows_on_gui == 1) {
        cancel = true;  // the click
        std::lock_guard<std::mutex> lock(m);
        click_seen = true;
        clicked.notify_all();
      }
    });
    std::unique_lock<std::mutex> lock(m);
    clicked.wait(lock, [&] { return click_seen; });
  };
  auto progress = [&](double f) { gui.post([&, f] { out.progress.push_back(f); }); };
  std::thread worker([&] {
    const size_t rows = run(row_done, progress, &cancel);
    gui.post([&, rows] {
      out.rows_returned = rows;
      out.worker_done = true;
    });
  });
  gui.run_until([&] { return out.worker_done; });
  worker.join();
  return out;
}

void expect_cancelled(const CancelledRun& r, size_t all_rows) {
  EXPECT_TRUE(r.worker_done);
  EXPECT_GE(r.rows_returned, 1u);
  EXPECT_LT(r.rows_returned, all_rows);
  EXPECT_EQ(r.rows_on_gui, r.rows_returned);
  for (size_t i = 1; i < r.progress.size(); ++i) EXPECT_GE(r.progress[i], r.progress[i - 1]);
  for (double f : r.progress) EXPECT_TRUE(f >= 0.0 && f <= 1.0) << f;
}

TEST(Concurrency, GridSweepCancelledFromTheGuiThread) {
  GridSweepOptions o;
  o.densities = {0.5f, 1.f, 2.f, 4.f};
  o.random_rays = 3000;
  o.camera_width = 24;
  o.camera_height = 18;
  o.reps = 1;
  auto r = run_and_cancel_after_first_row([&](auto row_done, auto, const std::atomic<bool>* cancel) {
    return run_grid_sweep(
               *scene(), o, [&](const GridSweepRow&) { row_done(); }, cancel)
        .rows.size();
  });
  expect_cancelled(r, o.densities.size());
}

TEST(Concurrency, StructureComparisonCancelledFromTheGuiThread) {
  StructureCompareOptions o;
  o.structures = {"grid", "bvh", "kd", "octree"};
  o.build.bvh.threads = 2;
  o.camera_width = 24;
  o.camera_height = 18;
  o.random_rays = 3000;
  o.reps = 1;
  auto r = run_and_cancel_after_first_row([&](auto row_done, auto progress, const std::atomic<bool>* cancel) {
    StructureCompareHooks hooks;
    hooks.row_done = [&](const StructureCompareRow&) { row_done(); };
    hooks.progress = progress;
    hooks.cancel = cancel;
    return compare_structures(*scene(), o, hooks).rows.size();
  });
  expect_cancelled(r, o.structures.size());
}

TEST(Concurrency, CostReportCancelledFromTheGuiThread) {
  CostReportOptions o;
  o.width = 24;
  o.height = 18;
  o.structures = {"grid", "bvh"};
  o.threads = 2;
  o.build.bvh.threads = 2;
  auto r = run_and_cancel_after_first_row([&](auto row_done, auto progress, const std::atomic<bool>* cancel) {
    CostReportHooks hooks;
    hooks.row_done = [&](const CostRow&) { row_done(); };
    hooks.progress = progress;
    hooks.cancel = cancel;
    return run_cost_report(*scene(), o, hooks).rows.size();
  });
  expect_cancelled(r, 5);  // brute force twice, each structure, adaptive sampling
}

TEST(Concurrency, AaReportCancelledFromTheGuiThread) {
  auto s = build("bvh", 2);
  AaReportOptions o;
  o.methods = {"none", "regular:2", "jitter:2", "regular:3"};
  o.reference = "jitter:3";
  o.width = 16;
  o.height = 12;
  o.seeds = 1;
  o.threads = 2;
  auto r = run_and_cancel_after_first_row([&](auto row_done, auto progress, const std::atomic<bool>* cancel) {
    AaReportHooks hooks;
    hooks.row_done = [&](const AaReport&, const AaReportRow&) { row_done(); };
    hooks.progress = progress;
    hooks.cancel = cancel;
    return run_aa_report(*s->scene, *s->accel, o, hooks).rows.size();
  });
  expect_cancelled(r, o.methods.size());
}

}  // namespace
}  // namespace raystep
