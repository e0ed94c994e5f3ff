#include "raystep/render/render.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <memory>
#include <mutex>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "raystep/render/antialiasing.h"
#include "raystep/render/camera.h"
#include "raystep/render/pixel_filter.h"
#include "raystep/render/pixel_samples.h"
#include "raystep/util/random.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

// A progress bar on stderr, drawn by its own thread from a counter of finished rows. It appears only after
// half a second (short renders stay silent) and is erased when the render ends.
class ProgressBar {
 public:
  ProgressBar(bool enabled, int total) : total_(total) {
    if (enabled && ::isatty(STDERR_FILENO)) thread_ = std::thread([this] { run(); });
  }
  ~ProgressBar() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_flag_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  void advance() { done_.fetch_add(1, std::memory_order_relaxed); }

 private:
  void run() {
    using namespace std::chrono;
    const auto start = steady_clock::now();
    bool drawn = false;
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, milliseconds(100), [this] { return done_flag_; })) {
      if (steady_clock::now() - start < milliseconds(500)) continue;
      const int kWidth = 40;
      const double f = double(done_.load(std::memory_order_relaxed)) / double(total_);
      const int filled = int(f * kWidth);
      std::fprintf(stderr, "\r[%.*s%*s] %3d%%", filled, "========================================",
                   kWidth - filled, "", int(f * 100.0));
      std::fflush(stderr);
      drawn = true;
    }
    if (drawn) {
      std::fprintf(stderr, "\r\033[K");  // erase the line
      std::fflush(stderr);
    }
  }

  const int total_;
  std::atomic<int> done_{0};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_flag_ = false;
  std::thread thread_;
};

void validate_options(const RenderOptions& options) {
  constexpr int kMaxSide = 1 << 15;
  if (options.width <= 0 || options.height <= 0 || options.width > kMaxSide || options.height > kMaxSide)
    throw InputError("", 0, "image size must lie in [1, " + std::to_string(kMaxSide) + "], got " +
                                std::to_string(options.width) + " x " + std::to_string(options.height));
  if (size_t(options.width) * size_t(options.height) > (size_t(1) << 26))
    throw InputError("", 0, "image too large: at most 2^26 pixels");
  if (options.threads < 0) throw InputError("", 0, "threads must be >= 0");
  validate(options.aa);
}

}  // namespace

RenderOptions render_options(const RenderSettings& settings) {
  RenderOptions o;
  o.aa = settings.aa;
  o.width = settings.width;
  o.height = settings.height;
  o.seed = settings.seed;
  return o;
}

RenderResult render_image(const Scene& scene, const Accelerator& accel, const RenderOptions& options) {
  validate_options(options);
  const auto start = std::chrono::steady_clock::now();
  const int width = options.width, height = options.height;
  const ProjectiveCamera camera(scene.camera, width, height);
  const WhittedTracer tracer(scene, accel);

  RenderResult result;
  result.image = Image(width, height);
  result.samples.assign(size_t(width) * size_t(height), 0);
  tbb::enumerable_thread_specific<RayCounts> thread_counts;  // summed per thread, combined at the end
  ProgressBar progress(options.progress, height);

  auto render_rows = [&](const tbb::blocked_range<int>& rows) {
    RayCounts& counts = thread_counts.local();
    const RadianceFn radiance = [&](float px, float py) {
      return tracer.trace_primary(camera.generate(px, py), &counts);
    };
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < width; ++x) {
        const uint64_t pixel = uint64_t(y) * uint64_t(width) + uint64_t(x);
        // The pixel's own stream: independent of scheduling, and the one the pixel inspector replays.
        Pcg32 rng = pixel_rng(options.seed, x, y, width);
        const PixelEstimate e = estimate_pixel(options.aa, x, y, rng, radiance);
        result.image.pixels[pixel] = e.value;
        result.samples[pixel] = e.samples;
      }
      progress.advance();
    }
  };

  // The tent filter (render/pixel_filter.h): every pixel of the image, and of the frame one pixel wide around
  // it that the border pixels' tents reach, casts its samples once; each sample is added to the (at most
  // four) pixels whose tents reach it, into the sum that belongs to its source row (the row above the pixel,
  // its own, the row below). No two source rows write the same sum, so the rows run in parallel, and the
  // three sums are added in order at the end: the same additions in the same order whatever the threads.
  const bool tent = options.aa.filter == AntiAliasing::Filter::tent;
  std::vector<FilterSum> by_row[3];
  if (tent)
    for (std::vector<FilterSum>& sums : by_row) sums.assign(result.samples.size(), FilterSum{});
  auto splat_rows = [&](const tbb::blocked_range<int>& rows) {
    RayCounts& counts = thread_counts.local();
    const RadianceFn radiance = [&](float px, float py) {
      return tracer.trace_primary(camera.generate(px, py), &counts);
    };
    for (int sy = rows.begin(); sy < rows.end(); ++sy) {
      for (int sx = -1; sx <= width; ++sx) {
        Pcg32 rng = pixel_rng(options.seed, sx, sy, width);
        const uint32_t n = cast_pixel_samples(options.aa, sx, sy, rng, radiance,
                                              [&](float px, float py, const glm::vec3& c) {
          const int x0 = int(std::floor(px - 0.5f)), y0 = int(std::floor(py - 0.5f));
          for (int ty = y0; ty <= y0 + 1; ++ty) {
            if (ty < 0 || ty >= height) continue;
            for (int tx = x0; tx <= x0 + 1; ++tx) {
              if (tx < 0 || tx >= width) continue;
              const float w = tent_weight(px - (float(tx) + 0.5f), py - (float(ty) + 0.5f));
              if (w > 0.f) by_row[sy - ty + 1][size_t(ty) * size_t(width) + size_t(tx)].add(w, c);
            }
          }
        });
        if (sx >= 0 && sx < width && sy >= 0 && sy < height)
          result.samples[size_t(sy) * size_t(width) + size_t(sx)] = n;
      }
      if (sy >= 0 && sy < height) progress.advance();
    }
  };

  // An explicit thread count is honoured even above the number of cores (TBB caps its workers at the core
  // count unless a global_control raises the cap).
  std::unique_ptr<tbb::global_control> allow;
  if (options.threads > tbb::info::default_concurrency())
    allow = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  size_t(options.threads));
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  if (!tent) {
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int>(0, height, 1), render_rows); });
  } else {
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int>(-1, height + 1, 1), splat_rows); });
    for (size_t i = 0; i < result.samples.size(); ++i) {
      FilterSum sum = by_row[0][i];
      sum.add(by_row[1][i]);
      sum.add(by_row[2][i]);
      result.image.pixels[i] = sum.value();
    }
  }

  thread_counts.combine_each([&](const RayCounts& c) { result.rays += c; });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace raystep
