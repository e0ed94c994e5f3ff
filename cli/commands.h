// The subcommands of `raystep`, as plain functions over option structs (no CLI11 here: main.cpp parses).
// Each returns the process exit code and throws raystep::InputError on bad input.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "raystep/accel/bvh_quality.h"
#include "raystep/accel/structure_options.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/multi_trace.h"
#include "raystep/trace/ray_request.h"
#include "value_parsers.h"

namespace raystep {
struct KdNodeEntry;
}

namespace raystep::cli {

// The acceleration structure and its build options (render, cast, trace).
struct StructureArgs {
  std::string accel = "bvol";
  std::optional<std::string> grid_res;  // "NX,NY,NZ"
  float grid_density = 3.f;             // d in max(nx, ny, nz) = d * cbrt(n)
  std::string grid_insert = "exact";    // exact | bbox
  // kd-tree (kd, kd-median)
  float kd_ti = 80.f, kd_tt = 1.f, kd_empty_bonus = 0.f;
  int kd_max_depth = 0;  // 0: max(8, 1.2 log2 N); with an empty bonus 8 + 1.3 log2 N
  int kd_leaf_size = 1;
  std::string kd_mailbox = "on";  // on | off
  // BVH (bvh, bvh-sweep, bvh-median, bvh-sbvh and the wide ones); t_i, t_t and the depth limit are the kd-tree's options (kd_max_depth 0:
  // the BVH's limit, kBvhMaxDepth)
  int bvh_bins = 16;
  int bvh_leaf = 1;
  int bvh_max_leaf = 16;
  std::string bvh_order = "entry";  // entry | axis
  float sbvh_alpha = 1e-5f;         // SBVH: spatial splits where the object split's overlap is above this
  float sbvh_budget = 1.f;          // SBVH: extra references at most this times the primitives
  // octree: K, the leaf size (its depth limit is --max-depth, kd_max_depth: 0 automatic, else 1..20)
  int octree_leaf = 8;
  // General BSP tree (bsp); t_i, t_t, --max-depth, --leaf-size and --mailbox are the kd-tree's options
  std::string bsp_directions = "both";  // both | kdop | autopartition
  int bsp_candidates = 16;
};

struct RenderArgs {
  std::string scene;   // scene JSON or bare OBJ mesh
  std::string output;  // .png or .pfm
  StructureArgs structure;
  std::string
      heatmap;  // cells | tests | mailbox | boxes: a heat map of per-pixel work instead of the picture
  std::optional<std::string> aa;    // overrides the scene's anti-aliasing
  std::optional<std::string> size;  // "WxH", overrides the scene's size
  int threads = 0;                  // 0: all cores
  std::optional<uint64_t> seed;
  std::string samples_map;  // optional PNG of per-pixel sample counts
};

struct CastArgs {
  std::string scene;
  std::string rays;
  std::string hits;
  StructureArgs structure;
  int threads = 1;
  int reps = 5;
};

struct RaysArgs {
  std::string scene;
  std::string kind;  // camera | random | edges
  uint64_t count = 100000;
  uint64_t seed = 1;
  std::optional<std::string> size;  // camera rays: "WxH", default the scene's size
  std::string output;
};

struct InfoArgs {
  std::string scene;
};

struct TraceArgs {
  std::string scene;
  StructureArgs structure;
  std::optional<std::string> pixel;  // "X,Y"
  std::optional<std::string> ray;    // "ox,oy,oz,dx,dy,dz"
  bool secondary = false;            // also the shadow, reflected and refracted rays the pixel spawns
  bool build_events = false;         // kd-trees: also stream every build event into the trace
  std::optional<std::string> size;   // image size for --pixel, default the scene's
  std::optional<std::string> aa;     // with --pixel: the anti-aliased pixel's samples ("scene": the scene's)
  std::optional<uint64_t> seed;      // with --aa: the sampling seed, default the scene's
  std::string format = "json";       // json | csv
  std::string output;
};

struct SahArgs {
  std::string scene;
  StructureArgs structure;  // the kd-tree options (t_i, t_t, empty bonus, depth, leaf size)
  std::optional<uint32_t> node;
  std::optional<std::string> path;  // "LRL...": L below, R above, from the root
  std::string output;               // .csv or .json
};

struct KdStatsArgs {
  std::string scene;
  StructureArgs structure;
  uint64_t lines = 100000;  // random lines for the entry probabilities
  uint64_t seed = 1;
  std::string csv;  // optional: every node's predicted and measured entry probability
  std::string quality_csv;  // bvh-stats, optional: the tree's quality metrics as one CSV row
  uint64_t rays = 65536;    // bvh-stats: camera rays (at most 256 x 256) and random rays for the measured cost
};

struct TraceInfoArgs {
  std::string trace;
  bool own_costs = false;  // a multi-walk trace: cost each walk by its structure's own t_t, t_i
};

// replay_commands.cpp: the replay states of a trace (the storyboard).
struct ReplayArgs {
  std::string trace;
  std::optional<int> step;      // none: every step
  std::optional<int> walk;      // a multi-walk trace's walk; none: all
  std::optional<int> ray;       // none: all
  std::string format = "text";  // text | json
  std::string output;           // empty: stdout
};

// lesson_commands.cpp: checking lessons headless, and a step as a raystep-gui command line.
struct LessonCheckArgs {
  std::vector<std::string> paths;  // lesson files or folders of them; none: lessons/
};
struct LessonCommandArgs {
  std::string file;
  int step = 0;  // 1-based
};
struct LessonAnswersArgs {
  std::string file;
};

// report_commands.cpp: `raystep aa-report`, speed against error for anti-aliasing (report/aa_report.h).
struct AaReportArgs {
  std::string scene;
  std::optional<std::string> methods;  // comma-separated anti-aliasing specs; default: default_aa_methods()
  std::string reference = "auto";      // exact | jitter:K | auto
  std::optional<std::string> size;     // "WxH", default the scene's
  int seeds = 5;                       // seeds of each random method (jitter, random)
  int threads = 0;                     // 0: all cores
  std::string accel = "grid";
  std::string output;  // the report folder
};

// structure_commands.cpp: the structures and the cost formula measured, each into a report folder.
struct CompareArgs {
  std::string scene;
  std::string accel = "brute,bvol,grid,kd,kd-median";
  uint64_t rays = 65536;            // random rays
  std::optional<std::string> size;  // camera rays "WxH" (default: the scene's, capped at 512)
  int reps = 3;
  std::string output;       // report folder
  StructureArgs structure;  // the BSP tree's options (--bsp-directions, --bsp-candidates); the others default
};
struct GridSweepArgs {
  std::string scene;
  std::optional<std::string> densities;  // "0.5,1,2,..." (default: 0.5 .. 8)
  uint64_t rays = 65536;
  std::optional<std::string> size;  // camera rays "WxH" (default: the scene's, capped at 256)
  int reps = 3;
  std::string output;
};
struct CostArgs {
  std::string scene;
  std::optional<std::string> size;
  std::optional<std::string> aa;
  std::optional<std::string> accel;  // structures (default: all but brute)
  int threads = 0;
  std::string output;  // optional report folder
};

// Shared by the commands (commands.cpp).
void check_output_folder(const std::string& path);

// One node of a binary tree (the first child follows its parent) as the entry-probability report shows it.
struct EntryNode {
  int depth = 0;
  int parent = -1;
  bool leaf = false;
  uint32_t prims = 0;         // the CSV's prims column
  uint32_t second_child = 0;  // inner nodes only
};

// kd-stats' and bvh-stats' entry probabilities, predicted against measured (entry, one per node): the top
// of the tree, then all nodes at once, the summary line ending in rays_note; every node to csv unless empty.
// The quality lines both tree commands print (accel/bvh_quality.h): the leaves by primitive count (the last
// bin: that many or more) and by depth, and the cost measured on the scene's camera rays (at most `rays`) and
// as many random rays against the SAH's prediction. Returns the two measurements (camera, random).
void print_leaf_histograms(const std::vector<uint64_t>& by_prims, const std::vector<uint64_t>& by_depth);
std::pair<MeasuredCost, MeasuredCost> print_measured_cost(const Accelerator& accel, const Scene& scene,
                                                          uint64_t rays, uint64_t seed, float t_i, float t_t,
                                                          double sah_cost);

void report_entry_probability(const std::vector<EntryNode>& nodes, const std::vector<KdNodeEntry>& entry,
                              uint64_t lines, size_t rays_cast, const char* rays_note,
                              const std::string& csv);
KdOptions kd_options(const StructureArgs& s);
BspOptions bsp_options(const StructureArgs& s);
BvhOptions bvh_options(const StructureArgs& s);  // InputError naming the option for a bad value
std::unique_ptr<Accelerator> build_structure(const StructureArgs& s);

int run_render(const RenderArgs& args);
int run_aa_report(const AaReportArgs& args);
int run_trace(const TraceArgs& args);
// `sah` on a 2D scene: one line saying that the structure cuts x and y only and that the CSV's area columns
// hold perimeters (p = L_child / L, Crofton in the plane); nothing for a 3D scene.
void print_plane_note(const Geometry& geometry);
// The ray of `trace` without --pixel: --ray (in a 2D scene also ox,oy,dx,dy), else a 2D scene's own ray;
// InputError when there is neither.
RayRequest trace_ray_by_hand(const TraceArgs& args, const Scene& scene);
int run_trace_info(const TraceInfoArgs& args);
int run_replay(const ReplayArgs& args);
// multi_trace_commands.cpp: `trace --accel A,B,...` (run_trace hands a list over) and trace-info on its file.
int run_multi_trace(const TraceArgs& args);
int run_multi_trace_info(const std::string& path, const MultiTrace& trace, bool own_costs);
int run_cast(const CastArgs& args);
int run_rays(const RaysArgs& args);
int run_info(const InfoArgs& args);
int run_sah(const SahArgs& args);
// bvh_commands.cpp: `raystep bvh-stats` and `raystep sah --accel bvh...`.
int run_bvh_stats(const KdStatsArgs& args);
int run_bvh_sah(const SahArgs& args);
// bsp_commands.cpp: `raystep sah --accel bsp` (one BSP node's candidates by orientation).
int run_bsp_sah(const SahArgs& args);
int run_kdtree_stats(const KdStatsArgs& args);
int run_compare(const CompareArgs& args);
int run_grid_sweep_command(const GridSweepArgs& args);
int run_cost(const CostArgs& args);
int run_lesson_check(const LessonCheckArgs& args);
int run_lesson_command(const LessonCommandArgs& args);
int run_lesson_answers(const LessonAnswersArgs& args);
int run_lesson_numbers(const LessonAnswersArgs& args);
int run_lesson_facts();

// export_commands.cpp: `raystep export-vtk`, the scene, a structure and recorded walks for ParaView
// (docs/vtk-export.md).
struct ExportVtkArgs {
  std::string scene;
  StructureArgs structure;           // accel "": the trace's structure (--trace), else required
  std::optional<std::string> pixel;  // "X,Y": record this pixel's primary ray
  bool secondary = false;            // with pixel: also its shadow, reflected and refracted rays
  std::optional<std::string> trace;  // a trace file of the same scene: its rays and the nodes it carries
  std::optional<std::string> size;   // image size WxH for --pixel (default: the scene's)
  uint64_t max_cells = 200000;       // bound on the structure's cells written (vtk_export::kDefaultMaxCells)
  std::string output;                // the folder (replaced atomically)
};
int run_export_vtk(const ExportVtkArgs& args);

// figure_commands.cpp: `raystep figure`, a 2D scene's structure and a walk at a step as SVG, PDF or PNG.
struct FigureArgs {
  std::string scene;
  StructureArgs structure;
  std::optional<std::string> ray;  // "ox,oy,dx,dy" (or six numbers); none: the scene's own ray
  std::optional<int> step;         // the event the walk is drawn after; none: its end
  std::optional<std::string> aa;   // the anti-aliasing figure instead (figure/flat_aa_figure.h)
  std::optional<std::string> size;  // its pixels WxH (default: the scene's)
  int width = 640;                 // points (SVG, PDF) or pixels (PNG)
  std::string output;              // .svg, .pdf or .png
};
int run_figure(const FigureArgs& args);

// html_commands.cpp: `raystep export-html`, a trace or a 2D scene's ray as a page that plays the walk in a
// browser.
struct ExportHtmlArgs {
  std::string input;                  // a trace .json, or a 2D scene .json
  StructureArgs structure;            // a 2D scene's structure
  std::optional<std::string> ray;     // a 2D scene: "ox,oy,dx,dy"; none: the scene's own ray
  std::optional<std::string> title;   // the page's heading
  int width = 560;                    // the picture's width in points (CSS pixels)
  std::string output;                 // page.html
};
int run_export_html(const ExportHtmlArgs& args);

// bvol_commands.cpp: `raystep bvol-report`, the kinds of bounding volumes on each scene's camera rays.
struct BvolReportArgs {
  std::vector<std::string> scenes;  // empty: scenes/*.json in the current folder
  std::optional<std::string> size;  // camera rays "WxH" (default: the scene's, at most 160 on a side)
  int reps = 3;
  std::string output;  // report folder (bvol_report.csv, bvol_report.md); empty: the table on stdout only
};
int run_bvol_report(const BvolReportArgs& args);

}  // namespace raystep::cli

namespace raystep::cli {

// hardcases_commands.cpp: `raystep hardcases [MESH]`, the hard-case battery for every structure. Exit codes:
// 0 no leak, disagreement or crash; 1 any of them; 2 bad input (InputError).
struct HardCasesArgs {
  std::string mesh;    // a .obj file; empty: the built-in meshes
  std::string accel;   // comma-separated structures, "all", or empty: brute,grid,kd,bvh,bvh-sbvh,bvh4,bvh8,bvh8-sbvh,octree,bsp
  std::string output;  // optional report file, .csv or .json
  uint64_t rays = 0;   // rays per scale on the mesh (0: automatic)
  uint64_t seed = 1;
  double time_limit = 300;  // seconds per structure before its run counts as a crash (a hang)
};
int run_hardcases(const HardCasesArgs& args);

}  // namespace raystep::cli
