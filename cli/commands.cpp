// The subcommands of `raystep`. See commands.h.
#include "commands.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <sstream>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/kdtree_entry_probability.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/structure_options.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/io/image_io.h"
#include "raystep/io/ray_files.h"
#include "raystep/io/scene_loader.h"
#include "raystep/render/camera.h"
#include "raystep/render/reference.h"
#include "raystep/render/render.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/trace/build_event_writer.h"
#include "raystep/trace/heatmap.h"
#include "raystep/trace/pixel_rays.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"
#include "raystep/util/memory_limit.h"

namespace raystep::cli {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

// Refuse an output whose folder does not exist before spending time on the work.
void check_output_folder(const std::string& path) {
  std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw InputError(path, 0, "cannot write: folder '" + parent.string() + "' does not exist");
}

KdOptions kd_options(const StructureArgs& s) {
  KdOptions kd;
  kd.t_i = s.kd_ti;
  kd.t_t = s.kd_tt;
  kd.empty_bonus = s.kd_empty_bonus;
  kd.max_depth = s.kd_max_depth;
  kd.leaf_size = s.kd_leaf_size;
  return kd;
}

BvhOptions bvh_options(const StructureArgs& s) {
  BvhOptions bvh;
  bvh.t_i = s.kd_ti;
  bvh.t_t = s.kd_tt;
  if (s.kd_max_depth < 0 || s.kd_max_depth > kBvhMaxDepth)
    throw InputError("", 0, "--max-depth must be 0.." + std::to_string(kBvhMaxDepth) + " (0: automatic)");
  bvh.max_depth = s.kd_max_depth == 0 ? kBvhMaxDepth : s.kd_max_depth;
  if (s.bvh_bins < 2 || s.bvh_bins > 256) throw InputError("", 0, "--bins must be 2..256");
  bvh.bins = s.bvh_bins;
  if (s.bvh_leaf < 1) throw InputError("", 0, "--bvh-leaf must be at least 1");
  bvh.leaf_size = s.bvh_leaf;
  if (s.bvh_max_leaf < s.bvh_leaf || s.bvh_max_leaf > int(BvhNode::kMaxCount))
    throw InputError("", 0,
                     "--bvh-max-leaf must be at least --bvh-leaf (" + std::to_string(s.bvh_leaf) + ")");
  bvh.max_leaf_size = s.bvh_max_leaf;
  if (s.bvh_order != "entry" && s.bvh_order != "axis")
    throw InputError("", 0, "--bvh-order '" + s.bvh_order + "': entry | axis");
  if (!std::isfinite(s.sbvh_alpha) || !(s.sbvh_alpha >= 0.f))
    throw InputError("", 0, "--sbvh-alpha must be a number >= 0");
  bvh.spatial_alpha = s.sbvh_alpha;
  if (!std::isfinite(s.sbvh_budget) || !(s.sbvh_budget >= 0.f) || s.sbvh_budget > 16.f)
    throw InputError("", 0, "--sbvh-budget must be in 0..16");
  bvh.spatial_budget = s.sbvh_budget;
  return bvh;
}

BspOptions bsp_options(const StructureArgs& s) {
  BspOptions bsp;
  if (!parse_bsp_directions(s.bsp_directions, &bsp.directions))
    throw InputError("", 0, "--bsp-directions '" + s.bsp_directions + "': both | kdop | autopartition");
  if (s.bsp_candidates < 1 || s.bsp_candidates > 4096)
    throw InputError("", 0, "--bsp-candidates must be 1..4096");
  bsp.candidates = s.bsp_candidates;
  bsp.t_i = s.kd_ti;
  bsp.t_t = s.kd_tt;
  if (s.kd_max_depth < 0 || s.kd_max_depth > kBspMaxDepth)
    throw InputError("", 0, "--max-depth must be 0.." + std::to_string(kBspMaxDepth) + " (0: automatic)");
  bsp.max_depth = s.kd_max_depth;
  bsp.leaf_size = s.kd_leaf_size;
  return bsp;
}

std::unique_ptr<Accelerator> build_structure(const StructureArgs& s) {
  StructureOptions options;
  if (!(s.grid_density > 0.f && s.grid_density <= 64.f))
    throw InputError("", 0, "--grid-density must be in (0, 64]");
  options.grid.density = s.grid_density;
  options.grid.exact_insert = s.grid_insert != "bbox";
  if (s.grid_res) {
    std::vector<float> n = parse_numbers("--grid-res", *s.grid_res, 3);
    std::array<int, 3> res;
    for (int a = 0; a < 3; ++a) {
      if (n[a] != std::floor(n[a]) || n[a] < 1 || n[a] > 4096)
        throw InputError("", 0,
                         "--grid-res '" + *s.grid_res + "': each of NX,NY,NZ must be a whole number 1..4096");
      res[a] = int(n[a]);
    }
    options.grid.resolution = res;
  }
  options.kd = kd_options(s);
  options.kd_mailboxes = s.kd_mailbox != "off";
  // The BVH's options are checked only for a BVH (the kd-tree's --max-depth keeps its own message).
  if (s.accel.rfind("bvh", 0) == 0) {
    options.bvh = bvh_options(s);
    options.bvh_order = s.bvh_order == "axis" ? BvhOrder::split_axis : BvhOrder::entry_distance;
  }
  if (s.accel == "octree") {
    if (s.octree_leaf < 1 || s.octree_leaf > (1 << 24))
      throw InputError("", 0, "--octree-leaf must be 1..16777216");
    if (s.kd_max_depth < 0 || s.kd_max_depth > kOctreeMaxDepth)
      throw InputError(
          "", 0,
          "--max-depth must be 0.." + std::to_string(kOctreeMaxDepth) + " for the octree (0: automatic)");
    options.octree.leaf_size = s.octree_leaf;
    options.octree.max_depth = s.kd_max_depth;
  }
  if (s.accel == "bsp") options.bsp = bsp_options(s);
  try {
    return make_accelerator(s.accel, options);
  } catch (const InputError& e) {
    throw InputError("", 0, "--accel: " + e.detail());
  }
}

// 0 (all cores) or an explicit count up to 256: TBB aborts the process on absurd counts (70,000 did).
void check_threads(int threads) {
  if (threads < 0 || threads > 256) throw InputError("", 0, "--threads must be 0..256 (0: all cores)");
}

int run_render(const RenderArgs& a) {
  std::string ext = extension(a.output);
  if (ext != ".png" && ext != ".pfm")
    throw InputError(a.output, 0, "unknown image format (use .png or .pfm)");
  check_output_folder(a.output);
  if (!a.samples_map.empty()) {
    if (extension(a.samples_map) != ".png") throw InputError(a.samples_map, 0, "the samples map is a .png");
    check_output_folder(a.samples_map);
  }
  check_threads(a.threads);

  Scene scene = load_scene(a.scene);
  RenderOptions opt;
  opt.aa = a.aa ? parse_antialiasing(*a.aa) : scene.render.aa;
  opt.width = scene.render.width;
  opt.height = scene.render.height;
  if (a.size) parse_size(*a.size, &opt.width, &opt.height);
  opt.threads = a.threads;
  opt.seed = a.seed ? *a.seed : scene.render.seed;
  opt.progress = true;
  auto accel = build_structure(a.structure);
  check_build_memory(a.scene, a.structure.accel, scene.geometry.size());

  auto t0 = Clock::now();
  accel->build(scene.geometry);
  double build_ms = ms_since(t0);

  if (!a.heatmap.empty()) {
    if (ext != ".png") throw InputError(a.output, 0, "a heat map is written as .png");
    HeatQuantity quantity = parse_heat_quantity(a.heatmap);
    auto t1 = Clock::now();
    HeatMap heat = compute_heatmap(scene.camera, *accel, opt.width, opt.height, quantity, opt.threads);
    double heat_ms = ms_since(t1);
    write_png(a.output, heatmap_image(heat));
    std::printf("heat map: %s per primary ray (one ray through each pixel's centre), %s, %dx%d\n",
                heat_quantity_label(quantity), accel->name().c_str(), opt.width, opt.height);
    std::printf("scale: 0 (dark blue, bottom of the colour bar) .. %u (yellow, top); mean %.2f\n",
                heat.max_value, heat.mean_value);
    std::printf("time: build %.1f ms, heat map %.1f ms\n", build_ms, heat_ms);
    std::printf("wrote %s\n", a.output.c_str());
    return 0;
  }
  RenderResult r = render_image(scene, *accel, opt);

  if (ext == ".png")
    write_png(a.output, r.image);
  else
    write_pfm(a.output, r.image);
  if (!a.samples_map.empty()) {
    uint32_t max_count = 0;
    write_png(a.samples_map, sample_count_image(r.samples, opt.width, opt.height, &max_count));
    std::printf("samples map: %s (black 0 .. yellow %u samples per pixel)\n", a.samples_map.c_str(),
                max_count);
  }

  uint64_t samples = 0;
  for (uint32_t s : r.samples) samples += s;
  double pixels = double(opt.width) * opt.height;
  std::printf("scene: %s (%zu primitives), accel %s, aa %s, %dx%d\n", scene.path.c_str(),
              scene.geometry.size(), accel->name().c_str(), to_string(opt.aa).c_str(), opt.width, opt.height);
  std::printf("rays: primary=%" PRIu64 " shadow=%" PRIu64 " reflected=%" PRIu64 " refracted=%" PRIu64
              " total=%" PRIu64 " (%.2f samples per pixel)\n",
              r.rays.primary, r.rays.shadow, r.rays.reflected, r.rays.refracted, r.rays.total(),
              double(samples) / pixels);
  std::printf("time: build %.1f ms, render %.1f ms\n", build_ms, r.seconds * 1e3);
  std::printf("wrote %s\n", a.output.c_str());
  return 0;
}

namespace {

// What an engineer comparing structures wants beside the speed: the grid's resolution and references per
// primitive (exact against bounding-box insertion), the kd-tree's and the BVH's size and depth, the wide
// BVH's kernel.
void print_structure_summary(const Accelerator& accel, size_t prims) {
  double per_prim = 1.0 / double(std::max<size_t>(prims, 1));
  if (auto* grid = dynamic_cast<const UniformGrid*>(&accel)) {
    std::array<int, 3> n = grid->resolution();
    std::printf("structure: grid %d x %d x %d cells", n[0], n[1], n[2]);
    if (grid->coarsened()) {
      // The density rule asked for more: say from what and why, so that the timing is not misread.
      std::array<int, 3> r = grid->requested_resolution();
      std::printf(" (coarsened from %d x %d x %d: %s of %zu)", r[0], r[1], r[2],
                  to_string(grid->coarsening()), UniformGrid::reference_budget(prims));
    }
    std::printf(", %zu references (%.3f per primitive), %s insertion\n", grid->reference_count(),
                double(grid->reference_count()) * per_prim, grid->options().exact_insert ? "exact" : "bbox");
  } else if (auto* kd = dynamic_cast<const KdTree*>(&accel)) {
    KdTreeStats st = kd_tree_stats(kd->data(), kd->options());
    std::printf(
        "structure: %s %zu nodes (%zu leaves, %zu empty), depth %d, %zu references (%.3f per primitive)\n",
        kd->name().c_str(), st.nodes, st.leaves, st.empty_leaves, st.max_depth, st.references,
        double(st.references) * per_prim);
  } else if (auto* bvh = dynamic_cast<const Bvh*>(&accel)) {
    BvhStats st = bvh_stats(bvh->data(), bvh->options());
    std::printf(
        "structure: %s %zu nodes (%zu leaves, %.2f primitives per leaf), depth %d, SAH cost %.1f, %zu "
        "bytes\n",
        bvh->name().c_str(), st.nodes, st.leaves, st.mean_leaf_prims, st.max_depth, st.sah_cost,
        bvh->memory_bytes());
  } else if (auto* octree = dynamic_cast<const Octree*>(&accel)) {
    OctreeStats st = octree_stats(octree->data());
    std::printf(
        "structure: octree %zu nodes (%zu leaves, %zu empty), depth %d (limit %d), %zu references (%.3f "
        "per primitive), leaves over K: %zu at the depth limit, %zu not reduced, %zu over budget\n",
        st.nodes, st.leaves, st.empty_leaves, st.max_depth, octree_max_depth(octree->options(), prims),
        st.references, double(st.references) * per_prim,
        st.leaves_by_reason[int(OctreeLeafReason::max_depth)],
        st.leaves_by_reason[int(OctreeLeafReason::no_reduction)],
        st.leaves_by_reason[int(OctreeLeafReason::budget)]);
  } else if (auto* wide = dynamic_cast<const WideBvh*>(&accel)) {
    // The kernel in use matters as much as the tree: the same walk runs at half the speed without AVX2.
    std::printf("structure: %s (%d-wide nodes, %s kernel), %zu bytes\n", wide->name().c_str(), wide->width(),
                WideBvh::simd_level(), wide->memory_bytes());
  }
}

}  // namespace

int run_cast(const CastArgs& a) {
  if (a.reps < 1 || a.reps > 1000) throw InputError("", 0, "--reps must be 1..1000");
  check_threads(a.threads);
  check_output_folder(a.hits);
  Scene scene = load_scene(a.scene);
  std::vector<Ray> rays = read_rays(a.rays);
  auto accel = build_structure(a.structure);
  check_build_memory(a.scene, a.structure.accel, scene.geometry.size());

  auto t0 = Clock::now();
  accel->build(scene.geometry);
  double build_ms = ms_since(t0);

  std::vector<Hit> hits(rays.size());
  auto trace_range = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) accel->intersect(rays[i], &hits[i]);
  };
  int threads = a.threads == 0 ? tbb::this_task_arena::max_concurrency() : a.threads;
  tbb::task_arena arena(threads);
  std::vector<double> times;
  for (int rep = 0; rep < a.reps; ++rep) {
    auto t1 = Clock::now();
    if (threads == 1) {
      trace_range(0, rays.size());
    } else {
      arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 1024),
                          [&](const tbb::blocked_range<size_t>& r) { trace_range(r.begin(), r.end()); });
      });
    }
    times.push_back(ms_since(t1));
  }
  std::sort(times.begin(), times.end());
  double trace_ms = times[times.size() / 2];
  write_hits(a.hits, hits);

  size_t found = std::count_if(hits.begin(), hits.end(), [](const Hit& h) { return h.found(); });
  print_structure_summary(*accel, scene.geometry.size());
  std::printf("hits: %zu of %zu rays; wrote %s\n", found, rays.size(), a.hits.c_str());
  std::printf("accel=%s prims=%zu rays=%zu build_ms=%.3f trace_ms=%.3f mrays_per_s=%.3f\n",
              accel->name().c_str(), scene.geometry.size(), rays.size(), build_ms, trace_ms,
              trace_ms > 0 ? double(rays.size()) / (trace_ms * 1e3) : 0.0);
  return 0;
}

int run_rays(const RaysArgs& a) {
  check_output_folder(a.output);
  if (a.kind != "camera" && a.count > (uint64_t(1) << 28))
    throw InputError("", 0, "--count must be at most 268435456");
  Scene scene = load_scene(a.scene);
  std::vector<Ray> rays;
  if (a.kind == "camera") {
    int w = scene.render.width, h = scene.render.height;
    if (a.size) parse_size(*a.size, &w, &h);
    rays = camera_rays(scene.camera, w, h);
  } else if (a.kind == "random") {
    rays = random_rays(scene.geometry.bounds(), a.count, a.seed);
  } else {
    rays = edge_rays(scene.geometry, a.count, a.seed);
  }
  write_rays(a.output, rays);
  std::printf("wrote %zu %s rays to %s\n", rays.size(), a.kind.c_str(), a.output.c_str());
  return 0;
}

int run_info(const InfoArgs& a) {
  Scene scene = load_scene(a.scene);
  const Geometry& g = scene.geometry;
  size_t degenerate = 0;
  for (uint32_t id = 0; id < g.size(); ++id) {
    if (g.type(id) != PrimType::triangle) continue;
    glm::vec3 n = triangle_normal(g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2));
    if (!(glm::dot(n, n) > 0.f)) ++degenerate;
  }
  const Bounds3& b = g.bounds();
  std::printf("scene: %s\n", scene.path.c_str());
  std::printf("primitives: %zu (%zu triangles, %zu spheres)\n", g.size(), g.triangle_count(),
              g.size() - g.triangle_count());
  std::printf("degenerate triangles: %zu\n", degenerate);
  std::printf("bounds: [%g, %g, %g] .. [%g, %g, %g]\n", b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
  if (scene.flat) {  // a 2D scene: its shapes, and the walls they stand as
    size_t by_kind[4] = {0, 0, 0, 0};
    for (const FlatShape& s : scene.flat->shapes) ++by_kind[int(s.kind)];
    std::printf(
        "2D scene: %zu shapes (%zu segments, %zu polylines, %zu polygons, %zu circles) in [%g, %g] .. [%g, "
        "%g]; "
        "walls across z in [-%g, %g]\n",
        scene.flat->shapes.size(), by_kind[0], by_kind[1], by_kind[2], by_kind[3], scene.flat->lo.x,
        scene.flat->lo.y, scene.flat->hi.x, scene.flat->hi.y, scene.flat->half_height,
        scene.flat->half_height);
  }
  std::printf("objects: %zu\n", g.objects().size());
  for (const Object& o : g.objects())
    std::printf("  %-28s primitives %u..%u  material %s\n", o.name.c_str(), o.first_prim,
                o.first_prim + o.prim_count - (o.prim_count ? 1 : 0),
                scene.materials[o.material].name.c_str());
  std::printf("materials: %zu, lights: %zu\n", scene.materials.size(), scene.lights.size());
  std::printf("render: %dx%d, aa %s, max depth %d\n", scene.render.width, scene.render.height,
              to_string(scene.render.aa).c_str(), scene.render.max_depth);
  return 0;
}

void print_plane_note(const Geometry& geometry) {
  if (geometry.split_space().plane())
    std::printf(
        "in the plane (a 2D scene): cuts on x and y only; the area columns hold perimeters, p = L_child / L "
        "(Crofton in the plane)\n");
}

RayRequest trace_ray_by_hand(const TraceArgs& a, const Scene& scene) {
  RayRequest r;
  if (a.ray) {
    const RayText t = parse_ray(*a.ray, scene.flat.has_value());
    r.ray.origin = glm::vec3(t.origin[0], t.origin[1], t.origin[2]);
    r.ray.direction = glm::vec3(t.direction[0], t.direction[1], t.direction[2]);
  } else if (scene.flat && scene.flat->has_ray) {
    r.ray = flat_ray(scene.flat->ray_origin, scene.flat->ray_direction);
  } else {
    throw InputError(
        "", 0,
        std::string("trace: give --pixel X,Y or --ray ") +
            (scene.flat ? "ox,oy,dx,dy (the scene has no ray of its own)" : "ox,oy,oz,dx,dy,dz"));
  }
  return r;
}

int run_trace(const TraceArgs& a) {
  if (a.structure.accel.find(',') != std::string::npos) return run_multi_trace(a);
  if (a.secondary && !a.pixel) throw InputError("", 0, "trace: --secondary goes with --pixel");
  if (a.aa && !a.pixel) throw InputError("", 0, "trace: --aa goes with --pixel");
  if (a.seed && !a.aa) throw InputError("", 0, "trace: --seed goes with --aa");
  if (a.build_events && a.format != "json")
    throw InputError("", 0, "trace: --build-events needs --format json");
  check_output_folder(a.output);
  // The anti-aliasing spec is checked before the scene is read: a typo costs nothing.
  std::optional<AntiAliasing> aa;
  if (a.aa && *a.aa != "scene") aa = parse_antialiasing(*a.aa);
  Scene scene = load_scene(a.scene);
  if (a.aa && *a.aa == "scene") aa = scene.render.aa;
  const uint64_t seed = a.seed ? *a.seed : scene.render.seed;
  auto accel = build_structure(a.structure);
  if (!records_events(*accel))
    throw InputError(
        "", 0,
        "trace: --accel " + a.structure.accel + " records no events (use " + recorded_structure_list() + ")");
  auto* kd = dynamic_cast<KdTree*>(accel.get());
  if (a.build_events && !kd)
    throw InputError("", 0, "trace: --build-events goes with --accel kd or kd-median");

  // The rays to record, checked before the (possibly long) build; pixel rays need the built structure.
  std::optional<RayRequest> by_hand;
  int w = scene.render.width, h = scene.render.height, px = 0, py = 0;
  if (!a.pixel) {
    by_hand = trace_ray_by_hand(a, scene);
  } else {
    if (a.size) parse_size(*a.size, &w, &h);
    std::vector<float> p = parse_numbers("--pixel", *a.pixel, 2);
    if (p[0] != std::floor(p[0]) || p[1] != std::floor(p[1]) || p[0] < 0 || p[1] < 0 || p[0] >= w ||
        p[1] >= h)
      throw InputError("", 0,
                       "--pixel '" + *a.pixel + "': outside the " + std::to_string(w) + "x" +
                           std::to_string(h) + " image");
    px = int(p[0]);
    py = int(p[1]);
  }
  auto record = [&]() {
    if (aa) {  // with the exact pre-filtered value, where the scene has one (render/reference.h)
      Trace t = record_pixel_trace(scene, *accel, w, h, px, py, *aa, seed, a.secondary, a.scene,
                                   file_content_hash(a.scene));
      t.pixel->exact = exact_pixel_value(scene, w, h, px, py, aa->filter);
      return t;
    }
    std::vector<RayRequest> requests;
    if (by_hand)
      requests.push_back(*by_hand);
    else
      requests = pixel_rays(scene, *accel, w, h, px, py, a.secondary);
    return record_trace(scene.geometry, *accel, requests, a.scene, file_content_hash(a.scene));
  };

  check_build_memory(a.scene, a.structure.accel, scene.geometry.size());
  Trace trace;
  if (a.build_events) {
    // The build is logged while it runs, straight into the (temporary) file: memory stays bounded.
    Trace opening;
    opening.scene_path = a.scene;
    opening.scene_hash = file_content_hash(a.scene);
    opening.scene_primitives = scene.geometry.size();
    size_t logged = 0;
    write_file_atomically(a.output, [&](std::ostream& out) {
      out << trace_json_opening(opening) << " \"build\": [";
      BuildEventWriter writer(out);
      kd->build(scene.geometry, writer);
      out << "\n ],\n";
      logged = writer.count();
      trace = record();
      out << trace_json_rest(trace);
    });
    std::printf("build: %zu events logged\n", logged);
  } else {
    accel->build(scene.geometry);
    trace = record();
    if (a.format == "csv")
      write_trace_csv(a.output, trace);
    else
      write_trace_json(a.output, trace);
  }
  std::printf("%s", trace_summary(trace).c_str());
  std::printf("wrote %s\n", a.output.c_str());
  return 0;
}

int run_sah(const SahArgs& a) {
  if (a.structure.accel.rfind("bvh", 0) == 0) return run_bvh_sah(a);
  if (a.structure.accel == "bsp") return run_bsp_sah(a);
  std::string ext = extension(a.output);
  if (ext != ".csv" && ext != ".json") throw InputError(a.output, 0, "the curve is written as .csv or .json");
  check_output_folder(a.output);
  Scene scene = load_scene(a.scene);
  KdOptions options = kd_options(a.structure);
  uint32_t node = a.node ? *a.node : 0;
  if (a.path) {
    KdTreeData tree = build_kdtree(scene.geometry, options);
    node = kd_node_by_path(tree, *a.path);
  }
  SahCurve curve = record_sah_curve(scene.geometry, options, node);
  if (ext == ".csv")
    write_sah_csv(a.output, curve);
  else
    write_sah_json(a.output, curve, options);
  const char* axes = "xyz";
  std::printf("node %u: depth %d, %u primitives, box [%g, %g, %g] .. [%g, %g, %g]\n", node, curve.info.depth,
              curve.n_prims, curve.info.box.lo.x, curve.info.box.lo.y, curve.info.box.lo.z,
              curve.info.box.hi.x, curve.info.box.hi.y, curve.info.box.hi.z);
  if (curve.leaf) {
    std::printf("decision: leaf (%s), leaf cost N*t_i = %g\n", leaf_reason_name(curve.leaf_reason),
                curve.leaf_cost);
    // What the rows mean for this leaf: only a leaf made by the cost rule has every row at N*t_i or above.
    switch (curve.leaf_reason) {
      case LeafReason::few_primitives:
        std::printf("  at most --leaf-size %d primitives: a leaf without a search, so no rows\n",
                    options.leaf_size);
        break;
      case LeafReason::max_depth:
        std::printf(
            "  the depth limit %d: a leaf without a search, so no rows (--max-depth sets the limit)\n",
            kd_max_depth(options, scene.geometry.size()));
        break;
      case LeafReason::no_cheaper_split:
        std::printf("  no plane costs less than N*t_i\n");
        break;
      case LeafReason::no_candidate:
        std::printf("  no plane lies strictly inside the node\n");
        break;
      case LeafReason::budget:
        std::printf(
            "  the reference budget (%g references a primitive) is spent here: the cheapest row may cost "
            "less than N*t_i, the budget, not the cost, stopped the split\n",
            options.reference_budget);
        break;
    }
  } else
    std::printf("decision: split %c = %.9g, cost %g against leaf cost N*t_i = %g\n", axes[curve.axis],
                curve.position, curve.cost, curve.leaf_cost);
  std::printf("candidates: %zu (t_i %g, t_t %g, empty bonus %g); wrote %s\n", curve.candidates.size(),
              options.t_i, options.t_t, options.empty_bonus, a.output.c_str());
  print_plane_note(scene.geometry);
  return 0;
}

void report_entry_probability(const std::vector<EntryNode>& nodes, const std::vector<KdNodeEntry>& entry,
                              uint64_t lines, size_t rays_cast, const char* rays_note,
                              const std::string& csv) {
  // Predicted against measured entry probabilities: the top of the tree, then all nodes at once.
  std::printf(
      "\nentry probability, %llu random lines through the root (Crofton: P(node) = S_node / S_root):\n",
      static_cast<unsigned long long>(lines));
  if (rays_cast < lines)
    std::printf(
        "  (rays: the first %zu of the lines only, %llu primitive tests in all: the leaves are crowded)\n",
        rays_cast, static_cast<unsigned long long>(kMaxEntryRayTests));
  std::printf("  %-8s %-7s %-10s %10s %10s %10s\n", "node", "depth", "path", "predicted", "lines", "rays");
  std::vector<std::string> paths(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (!nodes[i].leaf) {
      paths[i + 1] = paths[i] + "L";
      paths[nodes[i].second_child] = paths[i] + "R";
    }
    if (nodes[i].depth <= 3)
      std::printf("  %-8zu %-7d %-10s %10.4f %10.4f %10.4f\n", i, nodes[i].depth,
                  paths[i].empty() ? "(root)" : paths[i].c_str(), entry[i].predicted, entry[i].lines,
                  entry[i].rays);
  }
  double sum_abs = 0, worst = 0, sum_over = 0;
  size_t compared = 0;
  for (const KdNodeEntry& e : entry) {
    if (std::isnan(e.predicted)) continue;  // below a root of zero area
    sum_abs += std::fabs(e.predicted - e.lines);
    worst = std::max(worst, std::fabs(e.predicted - e.lines));
    sum_over += e.predicted - e.rays;
    ++compared;
  }
  double n = double(std::max<size_t>(compared, 1));
  std::printf("all %zu nodes: |predicted - lines| mean %.5f, max %.5f; predicted - rays mean %.5f %s\n",
              compared, sum_abs / n, worst, sum_over / n, rays_note);
  if (compared < entry.size())
    std::printf("(%zu nodes under a root of zero area have no predicted probability)\n",
                entry.size() - compared);
  if (!csv.empty()) {
    write_file_atomically(csv, [&](std::ostream& out) {
      out << "node,depth,parent,leaf,prims,predicted,lines,rays\n";
      char buf[160];
      for (size_t i = 0; i < nodes.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%zu,%d,%d,%d,%u,%.9g,%.9g,%.9g\n", i, nodes[i].depth, nodes[i].parent,
                      nodes[i].leaf ? 1 : 0, nodes[i].prims, entry[i].predicted, entry[i].lines,
                      entry[i].rays);
        out << buf;
      }
    });
    std::printf("wrote %s\n", csv.c_str());
  }
}

void print_leaf_histograms(const std::vector<uint64_t>& by_prims, const std::vector<uint64_t>& by_depth) {
  std::string hist;
  for (size_t k = 0; k < by_prims.size(); ++k)
    if (by_prims[k] > 0)
      hist += "  " + std::to_string(k) + (k + 1 == by_prims.size() ? "+" : "") + ": " + std::to_string(by_prims[k]);
  std::printf("leaves by primitive count:%s\n", hist.c_str());
  hist.clear();
  for (size_t k = 0; k < by_depth.size(); ++k)
    if (by_depth[k] > 0) hist += "  " + std::to_string(k) + ": " + std::to_string(by_depth[k]);
  std::printf("leaves by depth:%s\n", hist.c_str());
}

std::pair<MeasuredCost, MeasuredCost> print_measured_cost(const Accelerator& accel, const Scene& scene,
                                                          uint64_t rays, uint64_t seed, float t_i, float t_t,
                                                          double sah_cost) {
  int cw = scene.render.width, ch = scene.render.height;
  while (uint64_t(cw) * uint64_t(ch) > rays && cw > 1 && ch > 1) cw = (cw + 1) / 2, ch = (ch + 1) / 2;
  const std::vector<Ray> camera = camera_rays(scene.camera, cw, ch);
  const std::vector<Ray> random =
      scene.geometry.size() > 0 ? random_rays(scene.geometry.bounds(), rays, seed) : std::vector<Ray>{};
  const MeasuredCost mc = measure_cost(accel, camera, t_i, t_t);
  const MeasuredCost mr = measure_cost(accel, random, t_i, t_t);
  std::printf(
      "measured, %zu camera rays (%dx%d) / %zu random rays, per ray: inner nodes %.2f / %.2f, box tests %.2f / "
      "%.2f, primitive tests %.2f / %.2f; cost t_t nodes + t_i tests %.1f / %.1f (the SAH predicts %.1f for "
      "random lines through the root, which neither start inside the scene nor stop at a hit)\n",
      camera.size(), cw, ch, random.size(), mc.nodes_per_ray, mr.nodes_per_ray, mc.box_tests_per_ray,
      mr.box_tests_per_ray, mc.tests_per_ray, mr.tests_per_ray, mc.cost_per_ray, mr.cost_per_ray, sah_cost);
  return {mc, mr};
}

int run_kdtree_stats(const KdStatsArgs& a) {
  if (a.lines < 1 || a.lines > (uint64_t(1) << 26)) throw InputError("", 0, "--lines must be 1..67108864");
  if (a.rays < 1 || a.rays > (uint64_t(1) << 24)) throw InputError("", 0, "--rays must be 1..16777216");
  if (!a.csv.empty()) check_output_folder(a.csv);
  Scene scene = load_scene(a.scene);
  auto accel = build_structure(a.structure);
  auto* tree = dynamic_cast<KdTree*>(accel.get());
  auto t0 = Clock::now();
  tree->build(scene.geometry);
  double build_ms = ms_since(t0);
  const KdTreeData& d = tree->data();
  KdTreeStats st = kd_tree_stats(d, tree->options());
  size_t rays_cast = 0;
  std::vector<KdNodeEntry> entry = measure_entry_probability(*tree, a.lines, a.seed, &rays_cast);

  size_t prims = scene.geometry.size();
  double leaf_depth = 0, leaf_prims = 0;
  for (size_t i = 0; i < d.nodes.size(); ++i)
    if (d.nodes[i].is_leaf()) {
      leaf_depth += d.info[i].depth;
      leaf_prims += d.nodes[i].prim_count();
    }
  size_t full = st.leaves - st.empty_leaves;
  std::printf("scene: %s (%zu primitives), %s, built in %.1f ms\n", scene.path.c_str(), prims,
              tree->name().c_str(), build_ms);
  std::printf("nodes: %zu (%zu inner, %zu leaves of which %zu empty)\n", st.nodes, st.nodes - st.leaves,
              st.leaves, st.empty_leaves);
  std::printf("depth: max %d (limit %d), mean leaf depth %.2f\n", st.max_depth,
              kd_max_depth(tree->options(), prims), st.leaves ? leaf_depth / double(st.leaves) : 0.0);
  std::printf("primitives per non-empty leaf: mean %.2f, max %zu\n", full ? leaf_prims / double(full) : 0.0,
              st.max_leaf_prims);
  std::printf("references per primitive: %.3f (%zu references)\n",
              prims ? double(st.references) / double(prims) : 0.0, st.references);
  std::printf("SAH cost of the tree: %.3f (t_i %g, t_t %g); a single leaf would cost %.1f\n", st.sah_cost,
              tree->options().t_i, tree->options().t_t, double(prims) * tree->options().t_i);
  // The quality lines of bvh-stats that apply (a kd-tree's cells hold every triangle crossing them, so its
  // end-point overlap is 0 by construction).
  std::vector<uint64_t> by_prims(kLeafHistogramBins, 0), by_depth;
  for (size_t i = 0; i < d.nodes.size(); ++i)
    if (d.nodes[i].is_leaf()) {
      ++by_prims[std::min<size_t>(d.nodes[i].prim_count(), kLeafHistogramBins - 1)];
      if (by_depth.size() <= size_t(d.info[i].depth)) by_depth.resize(size_t(d.info[i].depth) + 1, 0);
      ++by_depth[size_t(d.info[i].depth)];
    }
  print_leaf_histograms(by_prims, by_depth);
  print_measured_cost(*tree, scene, a.rays, a.seed, tree->options().t_i, tree->options().t_t, st.sah_cost);

  std::vector<EntryNode> nodes(d.nodes.size());
  for (size_t i = 0; i < d.nodes.size(); ++i) {
    const KdNode& n = d.nodes[i];
    nodes[i] = {d.info[i].depth, d.info[i].parent, n.is_leaf(), n.is_leaf() ? n.prim_count() : 0u,
                n.is_leaf() ? 0u : n.above_child()};
  }
  report_entry_probability(nodes, entry, a.lines, rays_cast, "(rays stop at their first hit)", a.csv);
  return 0;
}

int run_trace_info(const TraceInfoArgs& a) {
  MultiTrace read = read_any_trace_json(a.trace);
  if (read.version >= kMultiTraceVersion) return run_multi_trace_info(a.trace, read, a.own_costs);
  const Trace& trace = read.walks.front();
  std::printf("%s: valid raystep trace, version %d\n", a.trace.c_str(), trace.version);
  std::printf("%s", trace_summary(trace).c_str());
  return 0;
}

}  // namespace raystep::cli
