// `raystep sah --accel bsp`: one general BSP node's candidate planes by orientation (the 13 k-DOP directions
// and the primitives' own planes), each with its SAH cost, written as CSV or JSON, and a summary per
// orientation on the terminal (how many candidates, the cheapest) so that "why this plane?" reads at a
// glance.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>

#include "commands.h"
#include "raystep/accel/bsp_sah_curve.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

namespace raystep::cli {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

const char* leaf_reason_text(BspLeafReason r) {
  switch (r) {
    case BspLeafReason::few_primitives:
      return "at most --leaf-size primitives: a leaf without a search, so no rows";
    case BspLeafReason::max_depth:
      return "the depth limit: a leaf without a search, so no rows (--max-depth sets the limit)";
    case BspLeafReason::no_area:
      return "the cell has no area: no plane can cut it";
    case BspLeafReason::no_cheaper_split:
      return "no plane costs less than N*t_i";
    case BspLeafReason::separates_nothing:
      return "the cheapest plane would leave every primitive on both sides";
    case BspLeafReason::budget:
      return "the reference budget is spent here: the cheapest row may cost less than N*t_i";
  }
  return "";
}

}  // namespace

int run_bsp_sah(const SahArgs& a) {
  const std::string ext = lower_extension(a.output);
  if (ext != ".csv" && ext != ".json") throw InputError(a.output, 0, "the curve is written as .csv or .json");
  BspOptions options = bsp_options(a.structure);
  check_output_folder(a.output);
  Scene scene = load_scene(a.scene);
  uint32_t node = a.node ? *a.node : 0;
  if (a.path) node = bsp_node_by_path(build_bsp(scene.geometry, options), *a.path);
  BspSahCurve curve = record_bsp_sah_curve(scene.geometry, options, node);
  if (ext == ".csv")
    write_bsp_sah_csv(a.output, curve);
  else
    write_bsp_sah_json(a.output, curve, options);

  const Bounds3& box = curve.info.box;
  std::printf("node %u: depth %d, %u primitives, cell area %g, cell box [%g, %g, %g] .. [%g, %g, %g]\n", node,
              curve.info.depth, curve.n_prims, curve.info.area, box.lo.x, box.lo.y, box.lo.z, box.hi.x,
              box.hi.y, box.hi.z);
  if (curve.leaf) {
    std::printf("decision: leaf (%s), leaf cost N*t_i = %g\n  %s\n", bsp_leaf_reason_name(curve.leaf_reason),
                curve.leaf_cost, leaf_reason_text(curve.leaf_reason));
  } else {
    const BspCandidate& c = curve.split;
    std::printf(
        "decision: split by the plane n.p = d, n = (%.6g, %.6g, %.6g) (%s, %s), d = %.9g: %u below, %u "
        "above, "
        "cost %g against leaf cost N*t_i = %g\n",
        c.plane.normal.x, c.plane.normal.y, c.plane.normal.z, bsp_direction_name(c.direction),
        bsp_plane_source_name(c.source), c.plane.offset, curve.n_below, curve.n_above, c.cost,
        curve.leaf_cost);
  }
  // Per orientation: how many candidates, and the cheapest (the chosen one is the cheapest of all).
  std::map<int, std::pair<int, const BspCandidate*>> by_direction;
  for (const BspCandidate& c : curve.candidates) {
    auto& [count, best] = by_direction[c.direction < 0 ? kBspKdopDirections : c.direction];
    ++count;
    if (!best || c.cost < best->cost) best = &c;
  }
  if (!by_direction.empty())
    std::printf("%-10s %10s %14s %14s\n", "direction", "candidates", "cheapest cost", "at offset");
  for (const auto& [dir, entry] : by_direction) {
    const BspCandidate& best = *entry.second;
    std::printf("%-10s %10d %14.6g %14.6g%s\n", bsp_direction_name(dir < kBspKdopDirections ? dir : -1),
                entry.first, best.cost, best.plane.offset, best.chosen ? "  <- chosen" : "");
  }
  std::printf("candidates: %zu (bsp, directions %s, %d per direction, t_i %g, t_t %g); wrote %s\n",
              curve.candidates.size(), bsp_directions_name(options.directions), options.candidates,
              options.t_i, options.t_t, a.output.c_str());
  print_plane_note(scene.geometry);
  return 0;
}

}  // namespace raystep::cli
