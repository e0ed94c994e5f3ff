// `raystep bvh-stats` (the BVH's shape, SAH cost, sibling overlap, and Crofton's entry probability predicted
// against measured) and `raystep sah --accel bvh|bvh-sweep|bvh-median` (one node's SAH curve).
#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "commands.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/bvh_entry_probability.h"
#include "raystep/accel/bvh_names.h"
#include "raystep/accel/bvh_quality.h"

#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

namespace raystep::cli {

namespace {

using Clock = std::chrono::steady_clock;

BvhBuilder builder_of(const std::string& accel) {
  std::optional<BvhName> name = parse_bvh_name(accel);
  if (name && name->width == 2) return name->builder;
  throw InputError("", 0, "--accel '" + accel + "': bvh | bvh-sweep | bvh-median | bvh-sbvh");
}

std::string extension(const std::string& path) {
  size_t dot = path.find_last_of('.');
  size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

int run_bvh_sah(const SahArgs& a) {
  std::string ext = extension(a.output);
  if (ext != ".csv" && ext != ".json") throw InputError(a.output, 0, "the curve is written as .csv or .json");
  BvhOptions options = bvh_options(a.structure);
  options.builder = builder_of(a.structure.accel);
  check_output_folder(a.output);
  Scene scene = load_scene(a.scene);
  uint32_t node = a.node ? *a.node : 0;
  if (a.path) node = bvh_node_by_path(build_bvh(scene.geometry, options), *a.path);
  BvhSahCurve curve = record_bvh_sah_curve(scene.geometry, options, node);
  if (ext == ".csv")
    write_bvh_sah_csv(a.output, curve);
  else
    write_bvh_sah_json(a.output, curve, options);
  const Bounds3& box = curve.bvh_node.box;
  std::printf("node %u: depth %d, %u primitives, box [%g, %g, %g] .. [%g, %g, %g]\n", node, curve.info.depth,
              curve.info.prims, box.lo.x, box.lo.y, box.lo.z, box.hi.x, box.hi.y, box.hi.z);
  if (curve.leaf) {
    std::printf("decision: leaf (%s), leaf cost N*t_i = %g\n", bvh_leaf_reason_name(curve.leaf_reason),
                curve.leaf_cost);
    switch (curve.leaf_reason) {
      case BvhLeafReason::few_primitives:
        std::printf("  at most --bvh-leaf %d primitives: a leaf without a search, so no rows\n",
                    options.leaf_size);
        break;
      case BvhLeafReason::max_depth:
        std::printf(
            "  the depth limit %d: a leaf without a search, so no rows (--max-depth sets the limit)\n",
            options.max_depth);
        break;
      case BvhLeafReason::no_cheaper_split:
        std::printf("  no candidate costs less than N*t_i (and N <= --bvh-max-leaf %d)\n",
                    options.max_leaf_size);
        break;
      case BvhLeafReason::no_candidate:
        std::printf("  every centroid is the same point: no plane separates them\n");
        break;
    }
  } else if (curve.chosen >= 0) {
    const BvhCandidate& c = curve.candidates[size_t(curve.chosen)];
    if (c.spatial)
      std::printf(
          "decision: spatial split %c at plane %.9g (bin %d of the node's box): %u references left, %u right "
          "(the primitives crossing the plane on both sides), cost %g against leaf cost N*t_i = %g\n",
          "xyz"[c.axis], c.position, c.bin, c.n_left, c.n_right, c.cost, curve.leaf_cost);
    else
      std::printf(
          "decision: split %c after %s %d (plane %.9g): %u left, %u right, cost %g against leaf cost N*t_i = "
          "%g\n",
          "xyz"[c.axis],
          options.builder == BvhBuilder::binned || options.builder == BvhBuilder::sbvh ? "bin" : "position",
          c.bin, c.position, c.n_left, c.n_right, c.cost, curve.leaf_cost);
    if (!(c.cost < curve.leaf_cost))
      std::printf("  (not cheaper than a leaf, but N > --bvh-max-leaf %d forces a split)\n",
                  options.max_leaf_size);
  }
  std::printf("candidates: %zu (%s, t_i %g, t_t %g, %d bins); wrote %s\n", curve.candidates.size(),
              a.structure.accel.c_str(), options.t_i, options.t_t, options.bins, a.output.c_str());
  print_plane_note(scene.geometry);
  return 0;
}

int run_bvh_stats(const KdStatsArgs& a) {
  if (a.lines < 1 || a.lines > (uint64_t(1) << 26)) throw InputError("", 0, "--lines must be 1..67108864");
  if (!a.csv.empty()) check_output_folder(a.csv);
  if (!a.quality_csv.empty()) check_output_folder(a.quality_csv);
  if (a.rays < 1 || a.rays > (uint64_t(1) << 24)) throw InputError("", 0, "--rays must be 1..16777216");
  BvhOptions options = bvh_options(a.structure);
  options.builder = builder_of(a.structure.accel);
  Scene scene = load_scene(a.scene);
  Bvh bvh(options);
  auto t0 = Clock::now();
  bvh.build(scene.geometry);
  double build_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  const BvhData& d = bvh.data();
  BvhStats st = bvh_stats(d, options);
  size_t rays_cast = 0;
  std::vector<BvhNodeEntry> entry = measure_bvh_entry_probability(bvh, a.lines, a.seed, &rays_cast);

  size_t prims = scene.geometry.size();
  double leaf_depth = 0;
  for (size_t i = 0; i < d.nodes.size(); ++i)
    if (d.nodes[i].is_leaf()) leaf_depth += d.info[i].depth;
  std::printf("scene: %s (%zu primitives), %s, built in %.1f ms\n", scene.path.c_str(), prims,
              bvh.name().c_str(), build_ms);
  std::printf("nodes: %zu (%zu inner, %zu leaves), %zu bytes\n", st.nodes, st.nodes - st.leaves, st.leaves,
              bvh.memory_bytes());
  std::printf("depth: max %d (limit %d), mean leaf depth %.2f\n", st.max_depth, options.max_depth,
              st.leaves ? leaf_depth / double(st.leaves) : 0.0);
  char per[32];
  std::snprintf(per, sizeof per, "%.3f", double(st.references) / double(std::max<size_t>(prims, 1)));
  const std::string placed = st.references == prims ? std::string("each primitive in one leaf")
                                                    : std::to_string(st.references) + " references, " + per +
                                                          " per primitive (spatial splits)";
  std::printf("primitives per leaf: mean %.2f, max %zu (leaf size %d, max leaf size %d); %s\n",
              st.mean_leaf_prims, st.max_leaf_prims, options.leaf_size, options.max_leaf_size, placed.c_str());
  const std::string bins = options.builder == BvhBuilder::binned || options.builder == BvhBuilder::sbvh
                               ? ", " + std::to_string(options.bins) + " bins"
                               : "";
  std::printf("SAH cost of the tree: %.3f (t_i %g, t_t %g%s); a single leaf would cost %.1f\n", st.sah_cost,
              options.t_i, options.t_t, bins.c_str(), double(prims) * options.t_i);
  std::printf(
      "sibling overlap: %.4f (sum over inner nodes of S(left box ∩ right box) / S(node), weighted by "
      "S(node) / S(root))\n",
      st.overlap);

  // Quality (accel/bvh_quality.h): EPO, the histograms, and the cost measured on rays against the SAH's.
  const BvhQuality q = tree_quality(bvh_view(d), scene.geometry, options.t_i, options.t_t);
  std::printf(
      "EPO (end-point overlap, Aila et al. 2013): %.4f = inner nodes %.4f + leaves %.4f (the cost, in t_t "
      "and t_i, of the boxes around a surface point whose subtree lacks its triangle; 0 without overlap)\n",
      q.epo, q.epo_inner, q.epo_leaves);
  print_leaf_histograms(q.leaf_prims, q.leaf_depth);
  const std::pair<MeasuredCost, MeasuredCost> measured =
      print_measured_cost(bvh, scene, a.rays, a.seed, options.t_i, options.t_t, q.sah_cost);
  const MeasuredCost &mc = measured.first, &mr = measured.second;
  if (!a.quality_csv.empty()) {
    write_file_atomically(a.quality_csv, [&](std::ostream& out) {
      out << "structure,primitives,nodes,inner,leaves,references,sah_cost,sibling_overlap,epo,epo_inner,"
             "epo_leaves,camera_rays,camera_nodes_per_ray,camera_box_tests_per_ray,camera_tests_per_ray,"
             "camera_cost_per_ray,random_rays,random_nodes_per_ray,random_box_tests_per_ray,"
             "random_tests_per_ray,random_cost_per_ray,leaf_prims,leaf_depth\n";
      char buf[640];
      std::snprintf(buf, sizeof buf,
                    "%s,%zu,%zu,%zu,%zu,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%" PRIu64 ",%.6g,%.6g,%.6g,%.6g,%" PRIu64
                    ",%.6g,%.6g,%.6g,"
                    "%.6g,",
                    bvh.name().c_str(), prims, q.nodes, q.inner, q.leaves, q.references, q.sah_cost, st.overlap,
                    q.epo, q.epo_inner, q.epo_leaves, mc.rays, mc.nodes_per_ray, mc.box_tests_per_ray,
                    mc.tests_per_ray, mc.cost_per_ray, mr.rays, mr.nodes_per_ray, mr.box_tests_per_ray,
                    mr.tests_per_ray, mr.cost_per_ray);
      out << buf;
      // The histograms as counts joined by ';' (index = primitives, or depth).
      auto joined = [](const std::vector<uint64_t>& v) {
        std::string s;
        for (size_t k = 0; k < v.size(); ++k) s += (k ? ";" : "") + std::to_string(v[k]);
        return s;
      };
      out << joined(q.leaf_prims) << ',' << joined(q.leaf_depth) << '\n';
    });
    std::printf("wrote %s\n", a.quality_csv.c_str());
  }

  std::vector<EntryNode> nodes(d.nodes.size());
  for (size_t i = 0; i < d.nodes.size(); ++i) {
    const BvhNode& n = d.nodes[i];
    nodes[i] = {d.info[i].depth, d.info[i].parent, n.is_leaf(), d.info[i].prims,
                n.is_leaf() ? 0u : n.second_child()};
  }
  report_entry_probability(nodes, entry, a.lines, rays_cast,
                           "(rays stop at their first hit and skip boxes beyond it)", a.csv);
  return 0;
}

}  // namespace raystep::cli
