// The facts a lesson's numbers read (lesson_facts.h): one table, each entry a name, its help and how it is
// computed from the step's world. The costly ones run the same reports as `raystep cost` and `raystep
// aa-report`, kept for the process: a lesson asks several numbers of one report.
#include "raystep/lesson/lesson_facts.h"

#include <cmath>
#include <cstdlib>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <functional>
#include <map>
#include <mutex>
#include <optional>

#include "raystep/accel/bsp.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/kdtree_entry_probability.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/random_lines.h"
#include "raystep/render/antialiasing.h"
#include "raystep/render/reference.h"
#include "raystep/report/aa_report.h"
#include "raystep/report/bvol_report.h"
#include "raystep/report/cost_report.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

// A report computed once per key for the whole process (each call site its own table: `make` is its lambda).
template <class T, class Make>
std::shared_ptr<const T> memoised(const std::string& key, Make make) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const T>> memo;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = memo[key];
  if (!slot) slot = std::make_shared<const T>(make());
  return slot;
}

}  // namespace

struct LessonFacts::Impl {
  const StepWorld& w;
  const LessonState& s;
  std::map<std::string, double> values;
  std::shared_ptr<const SahCurve> curve;
  std::shared_ptr<const CostReport> cost;
  std::shared_ptr<const AaReport> aa_report;
  std::shared_ptr<const std::vector<BvolReportRow>> bvol;
  std::shared_ptr<const std::vector<KdNodeEntry>> entries;
  Impl(const StepWorld& world, const LessonState& state) : w(world), s(state) {}

  [[noreturn]] static void fail(const std::string& what) { throw InputError("", 0, what); }

  AntiAliasing aa() const {
    if (!s.aa.empty() && s.aa != "scene") return parse_antialiasing(s.aa);
    return w.scene->render.aa;
  }
  const TracedRay& ray() const {
    if (!w.trace) fail("no traced pixel (pixel: X,Y)");
    return w.trace->rays[size_t(w.ray)];
  }
  const Event& event() const {
    const TracedRay& r = ray();
    return r.events[size_t(w.step)];
  }
  const TracePixel& pixel() const {
    if (!w.trace || !w.trace->pixel) fail("the traced pixel is not anti-aliased (aa: regular:K, ...)");
    return *w.trace->pixel;
  }
  // The pixel's exact value, as the inspector shows it (render/reference.h).
  double exact() const { return exact(aa().filter); }
  double exact(AntiAliasing::Filter filter) const {
    if (!w.pixel) fail("no traced pixel (pixel: X,Y)");
    const std::optional<glm::vec3> v =
        exact_pixel_value(*w.scene, w.width, w.height, (*w.pixel)[0], (*w.pixel)[1], filter);
    if (!v)
      fail("the scene has no exact reference (" +
           exact_coverage_unavailable(*w.scene, w.width, w.height, filter) + ")");
    return double(v->x);
  }
  const AdaptiveSquare& square() const {
    const TracePixel& p = pixel();
    if (!s.square) fail("no adaptive square selected (square: N)");
    return p.sampling.squares[size_t(*s.square)];
  }
  const UniformGrid& grid() const {
    const auto* g = dynamic_cast<const UniformGrid*>(w.accel.get());
    if (!g) fail("the structure is not the grid (accel: grid)");
    return *g;
  }
  // The selected node's SAH curve: a kd-tree's, or a binary BVH's in the kd-tree's terms (N below and above
  // for left and right; an SBVH's spatial candidates included).
  const SahCurve& node_curve() {
    const auto* kd = dynamic_cast<const KdTree*>(w.accel.get());
    const auto* bvh = dynamic_cast<const Bvh*>(w.accel.get());
    if (!kd && !bvh) fail("the structure is not a kd-tree or a binary BVH (accel: kd or bvh)");
    if (w.node < 0) fail("no tree node selected (node: ID, node-path: LR... or panel: sah)");
    if (!curve && kd)
      curve = std::make_shared<SahCurve>(record_sah_curve(kd->geometry(), kd->options(), uint32_t(w.node)));
    if (!curve && bvh)
      curve = std::make_shared<SahCurve>(
          as_kd_curve(record_bvh_sah_curve(bvh->geometry(), bvh->options(), uint32_t(w.node)), true));
    return *curve;
  }
  const SahCandidate& chosen() {
    const SahCurve& c = node_curve();
    if (c.chosen < 0) fail("node " + std::to_string(w.node) + " is a leaf: it has no split");
    return c.candidates[size_t(c.chosen)];
  }
  struct TreeShape {
    double nodes = 0, leaves = 0, empty_leaves = 0, depth = 0, references = 0, sah_cost = NAN;
  };
  // The tree's shape, measured once per step however many tree.* facts the step writes.
  const TreeShape& tree() {
    if (!shape) shape = measureTree();
    return *shape;
  }
  std::optional<TreeShape> shape;
  TreeShape measureTree() const {
    TreeShape t;
    const Accelerator* a = w.accel.get();
    if (const auto* kd = dynamic_cast<const KdTree*>(a)) {
      const KdTreeStats st = kd_tree_stats(kd->data(), kd->options());
      t = {double(st.nodes), double(st.leaves), double(st.empty_leaves), double(st.max_depth),
           double(st.references), st.sah_cost};
    } else if (const auto* bvh = dynamic_cast<const Bvh*>(a)) {
      const BvhStats st = bvh_stats(bvh->data(), bvh->options());
      t = {double(st.nodes), double(st.leaves), 0, double(st.max_depth), double(bvh->data().prim_index.size()),
           st.sah_cost};
    } else if (const auto* oc = dynamic_cast<const Octree*>(a)) {
      const OctreeStats st = octree_stats(oc->data());
      t = {double(st.nodes), double(st.leaves), double(st.empty_leaves), double(st.max_depth),
           double(st.references), NAN};
    } else if (const auto* bsp = dynamic_cast<const BspTree*>(a)) {
      const BspTreeStats st = bsp_tree_stats(bsp->data(), bsp->options());
      t = {double(st.nodes), double(st.leaves), double(st.empty_leaves), double(st.max_depth),
           double(st.references), st.sah_cost};
    } else {
      fail("the structure is not a tree (accel: kd, bvh, octree or bsp)");
    }
    return t;
  }
  BspTreeStats bsp() const {
    const auto* b = dynamic_cast<const BspTree*>(w.accel.get());
    if (!b) fail("the structure is not the BSP tree (accel: bsp)");
    return bsp_tree_stats(b->data(), b->options());
  }
  double events(const TracedRay& r, const std::string& type, size_t end) const {
    EventType t;
    if (!parse_event_type(type, &t)) fail("'" + type + "' is no event type (cell, node, prim_test, ...)");
    double n = 0;
    for (size_t i = 0; i < end && i < r.events.size(); ++i) n += r.events[i].type == t;
    return n;
  }

  // Möller–Trumbore's barycentrics (float, as its kernel computes them, without its early exits) for the
  // K-th (1-based, as text) primitive test of the current ray: the non-watertight test beside raystep's.
  glm::vec2 moller(const std::string& k_text) const {
    const TracedRay& r = ray();
    char* end = nullptr;
    const long k = std::strtol(k_text.c_str(), &end, 10);
    if (k_text.empty() || *end != 0 || k < 1) fail("'" + k_text + "': expected the test's number, 1, 2, ...");
    long seen = 0;
    for (const Event& e : r.events) {
      if (e.type != EventType::prim_test || ++seen != k) continue;
      for (const TracePrimitive& p : w.trace->primitives) {
        if (p.id != e.prim) continue;
        if (p.type != PrimType::triangle) fail("primitive test " + k_text + " is not a triangle's");
        const glm::vec3 e1 = p.v[1] - p.v[0], e2 = p.v[2] - p.v[0];
        const glm::vec3 pvec = glm::cross(r.ray.direction, e2);
        const float inv_det = 1.f / glm::dot(e1, pvec);
        const glm::vec3 tvec = r.ray.origin - p.v[0];
        const glm::vec3 qvec = glm::cross(tvec, e1);
        return {glm::dot(tvec, pvec) * inv_det, glm::dot(r.ray.direction, qvec) * inv_det};
      }
      fail("the trace lists no primitive " + std::to_string(e.prim));
    }
    fail("the ray has fewer than " + k_text + " primitive tests");
  }

  // The reports, kept for the process: keyed by everything they depend on.
  std::string report_key() const {
    return s.scene + "|" + file_content_hash(s.scene) + "|" + std::to_string(w.width) + "x" +
           std::to_string(w.height) + "|" + to_string(aa()) + "|" + structure_key(s.accel, s.structure);
  }
  const CostReport& cost_report() {
    if (!cost)
      cost = memoised<CostReport>(report_key(), [&] {
        CostReportOptions o;
        o.width = w.width;
        o.height = w.height;
        o.aa = aa();
        o.build = s.structure;
        return run_cost_report(*w.scene, o);
      });
    return *cost;
  }
  const AaReport& aa_rep() {
    if (!aa_report)
      aa_report = memoised<AaReport>(report_key(), [&] {
        AaReportOptions o;
        o.width = w.width;
        o.height = w.height;
        return run_aa_report(*w.scene, *w.accel, o);
      });
    return *aa_report;
  }
  const CostRow& cost_row(const std::string& which) {
    const CostReport& r = cost_report();
    for (const CostRow& row : r.rows)
      if (row.label == which) return row;
    for (const CostRow& row : r.rows)  // a structure's name: its row with adaptive termination
      if (row.label.rfind(which + ", ", 0) == 0) return row;
    std::string labels;
    for (const CostRow& row : r.rows) labels += (labels.empty() ? "" : ", ") + row.label;
    fail("the cost report has no row '" + which + "' (rows: " + labels + ")");
  }
  const CostFactor& cost_factor(const std::string& which) {
    const CostReport& r = cost_report();
    for (const CostFactor& f : r.factors)
      if (f.technique == which || f.technique == "acceleration: " + which ||
          f.technique.rfind(which + " (", 0) == 0)
        return f;
    std::string names;
    for (const CostFactor& f : r.factors) names += (names.empty() ? "" : ", ") + f.technique;
    fail("the cost report has no technique '" + which + "' (techniques: " + names + ")");
  }
  const BvolReportRow& bvol_row(const std::string& kind) {
    if (!bvol)
      bvol = memoised<std::vector<BvolReportRow>>(s.scene + "|" + file_content_hash(s.scene), [&] {
        BvolReportOptions o;
        o.reps = 1;  // the counts do not depend on the timing passes
        return run_bvol_report(*w.scene, o);
      });
    std::string kinds;
    for (const BvolReportRow& row : *bvol) {
      if (row.kind == kind) return row;
      kinds += (kinds.empty() ? "" : ", ") + row.kind;
    }
    fail("the bounding-volume report has no kind '" + kind + "' (kinds: " + kinds + ")");
  }
  // Crofton's theorem on the kd-tree (`raystep kdtree-stats`): its node at a path, its predicted entry
  // probability S_node / S_root, and the fractions of 100,000 random lines through the root that cross it
  // and, cast as rays, enter it.
  const KdTree& kd() const {
    const auto* kd = dynamic_cast<const KdTree*>(w.accel.get());
    if (!kd) fail("the structure is not a kd-tree (accel: kd)");
    return *kd;
  }
  uint32_t kd_node(const std::string& path) const {
    return kd_node_by_path(kd().data(), path == "root" ? std::string() : path);
  }
  const KdNodeEntry& entry(const std::string& path) {
    const uint32_t id = kd_node(path);
    if (!entries)
      entries = memoised<std::vector<KdNodeEntry>>(report_key() + "|entry", [&] {
        return measure_entry_probability(kd(), 100000, 1);
      });
    return (*entries)[id];
  }
  const AaReportRow& aa_row(const std::string& spec) {
    const AaReport& r = aa_rep();
    for (const AaReportRow& row : r.rows)
      if (row.spec == spec) return row;
    fail("the aa-report measures no method '" + spec + "' (see `raystep aa-report --help`)");
  }
};

namespace {

using Getter = std::function<double(LessonFacts::Impl&)>;
using Function = std::function<double(LessonFacts::Impl&, const std::string&)>;

struct Fact {
  LessonFactInfo info;
  Getter get;
  Function call;
};

double nonzero(double v, const char* what) {
  if (!(v > 0)) throw InputError("", 0, std::string(what) + " is 0");
  return v;
}

const std::vector<Fact>& facts() {
  using I = LessonFacts::Impl;
  auto fact = [](const char* name, const char* help, Getter g) { return Fact{{name, false, false, help}, g, {}}; };
  auto costly = [](const char* name, const char* help, Getter g) { return Fact{{name, false, true, help}, g, {}}; };
  auto fn = [](const char* name, bool is_costly, const char* help, Function f) {
    return Fact{{name, true, is_costly, help}, {}, f};
  };
  static const std::vector<Fact> table = {
      // The scene and the picture.
      fact("scene.primitives", "primitives in the scene (n)", [](I& i) { return double(i.w.scene->geometry.size()); }),
      fact("scene.lights", "point lights (L)", [](I& i) { return double(i.w.scene->lights.size()); }),
      fact("scene.depth", "the ray tree's depth limit (render.max_depth, d)",
           [](I& i) { return double(i.w.scene->render.max_depth); }),
      fact("scene.min_weight", "adaptive ray termination's threshold",
           [](I& i) { return double(i.w.scene->render.min_weight); }),
      fact("picture.width", "the picture's width in pixels", [](I& i) { return double(i.w.width); }),
      fact("picture.height", "the picture's height in pixels", [](I& i) { return double(i.w.height); }),
      fact("picture.pixels", "width x height (m^2)", [](I& i) { return double(i.w.width) * i.w.height; }),
      // The anti-aliasing settings of the step.
      fact("aa.k", "regular, jitter: k (k x k samples); random: N", [](I& i) { return double(i.aa().k); }),
      fact("aa.threshold", "adaptive: the contrast threshold T", [](I& i) { return double(i.aa().threshold); }),
      fact("aa.depth", "adaptive: the subdivision depth D", [](I& i) { return double(i.aa().max_depth); }),
      fact("aa.max_samples", "the most samples the settings spend on one pixel",
           [](I& i) { return double(max_samples_per_pixel(i.aa())); }),
      // The traced pixel's anti-aliasing (aa other than none).
      fact("pixel.samples", "samples the traced pixel took",
           [](I& i) { return double(i.pixel().sampling.samples.size()); }),
      fact("pixel.squares", "adaptive: squares of the pixel's subdivision",
           [](I& i) { return double(i.pixel().sampling.squares.size()); }),
      fact("pixel.value", "the pixel's value (red channel; grey scenes: the grey)",
           [](I& i) { return double(i.pixel().sampling.value.x); }),
      fact("pixel.box_value", "the mean of the pixel's own samples (red channel): its value with the box filter",
           [](I& i) { return double(i.pixel().sampling.box_value.x); }),
      fact("pixel.neighbour_samples", "tent filter: the neighbours' samples that the pixel's tent reaches",
           [](I& i) { return double(i.pixel().sampling.neighbours.size()); }),
      fact("pixel.own_weight", "tent filter: the share of the weight on the pixel's own samples",
           [](I& i) {
             const PixelSampling& s = i.pixel().sampling;
             double own = 0, all = 0;
             for (const PixelSample& p : s.samples) own += p.weight;
             all = own;
             for (const PixelSample& p : s.neighbours) all += p.weight;
             return all > 0 ? own / all : 0.0;
           }),
      fact("pixel.lit", "samples whose value is above one half (red channel)",
           [](I& i) {
             double n = 0;
             for (const PixelSample& p : i.pixel().sampling.samples) n += p.colour.x > 0.5f;
             return n;
           }),
      fact("pixel.exact", "the exact pre-filtered value with the step's filter (red channel), where there is one",
           [](I& i) { return i.exact(); }),
      fact("pixel.area", "the pixel's exact area coverage, the box pre-filter's value (red channel), whatever the filter",
           [](I& i) { return i.exact(AntiAliasing::Filter::box); }),
      fact("pixel.error", "|value - exact| (red channel)",
           [](I& i) { return std::abs(double(i.pixel().sampling.value.x) - i.exact()); }),
      fact("square.depth", "adaptive: the selected square's depth (0: the whole pixel)",
           [](I& i) { return double(i.square().depth); }),
      fact("square.new_samples", "adaptive: samples the square cast itself (the others are shared)",
           [](I& i) { return double(i.square().new_samples); }),
      fact("square.contrast", "adaptive: the square's largest contrast over the channels",
           [](I& i) {
             const glm::vec3 c = i.square().contrast;
             return double(std::max(c.x, std::max(c.y, c.z)));
           }),
      // The current ray and event.
      fact("trace.rays", "rays in the traced pixel's trace", [](I& i) {
        if (!i.w.trace) I::fail("no traced pixel (pixel: X,Y)");
        return double(i.w.trace->rays.size());
      }),
      fact("ray.depth", "the current ray's depth in its ray tree", [](I& i) { return double(i.ray().depth); }),
      fact("ray.events", "the current ray's events", [](I& i) { return double(i.ray().events.size()); }),
      fact("ray.t_hit", "the current ray's nearest hit's t (its ray_end)",
           [](I& i) {
             const Event& e = i.ray().events.back();
             if (e.prim < 0) I::fail("the ray misses");
             return double(e.t);
           }),
      fn("ray.count", false, "events of the current ray of a type: ray.count(\"prim_test\")",
         [](I& i, const std::string& t) { return i.events(i.ray(), t, i.ray().events.size()); }),
      fn("walk.count", false, "events of a type so far, the current one included: walk.count(\"cell\")",
         [](I& i, const std::string& t) { return i.events(i.ray(), t, size_t(i.w.step) + 1); }),
      fn("ray.moller_u", false, "Moller-Trumbore's u at the ray's K-th primitive test: ray.moller_u(\"1\")",
         [](I& i, const std::string& k) { return double(i.moller(k).x); }),
      fn("ray.moller_v", false, "Moller-Trumbore's v there", [](I& i, const std::string& k) { return double(i.moller(k).y); }),
      fn("ray.moller_uv", false, "Moller-Trumbore's u + v there (the floats' exact sum, as the Why text gives it)",
         [](I& i, const std::string& k) {
           const glm::vec2 b = i.moller(k);
           return double(b.x) + double(b.y);
         }),
      fact("event.index", "the current event's index", [](I& i) { return double(i.w.step); }),
      fact("event.t_enter", "cell event: t where the ray enters the cell", [](I& i) { return double(i.event().t_enter); }),
      fact("event.t_exit", "cell event: t where it leaves the cell", [](I& i) { return double(i.event().t_exit); }),
      fact("event.t_max_x", "cell event: tMax along x", [](I& i) { return double(i.event().t_max.x); }),
      fact("event.t_max_y", "cell event: tMax along y", [](I& i) { return double(i.event().t_max.y); }),
      fact("event.t_max_z", "cell event: tMax along z", [](I& i) { return double(i.event().t_max.z); }),
      fact("event.t_min", "node, push, pop event: the interval's start", [](I& i) { return double(i.event().t_min_node); }),
      fact("event.t_max", "node, push, pop event: the interval's end", [](I& i) { return double(i.event().t_max_node); }),
      fact("event.t", "prim_test, hit event: the hit's t", [](I& i) { return double(i.event().t); }),
      fact("event.node", "node, push, pop, leaf event: the node id", [](I& i) { return double(i.event().node); }),
      fact("event.depth", "node event: the node's depth", [](I& i) { return double(i.event().depth); }),
      // The selected kd-tree node's split (the SAH inspector's numbers).
      fact("node.id", "the selected node's id (a kd-tree's: its place in the depth-first build order)",
           [](I& i) { return double(i.node_curve().node); }),
      fact("node.prims", "primitives in the node (N)", [](I& i) { return double(i.node_curve().n_prims); }),
      fact("node.depth", "the node's depth", [](I& i) { return double(i.node_curve().info.depth); }),
      fact("node.candidates", "candidate planes evaluated", [](I& i) { return double(i.node_curve().candidates.size()); }),
      fact("node.leaf_cost", "N t_i: the cost of making it a leaf", [](I& i) { return double(i.node_curve().leaf_cost); }),
      fact("node.best", "the cheapest candidate's cost (a leaf's too)",
           [](I& i) {
             const SahCurve& c = i.node_curve();
             if (c.candidates.empty()) I::fail("node " + std::to_string(i.w.node) + " has no candidate plane");
             double best = INFINITY;
             for (const SahCandidate& x : c.candidates) best = std::min(best, double(x.cost));
             return best;
           }),
      fact("node.cost", "the chosen split's SAH cost", [](I& i) { return double(i.chosen().cost); }),
      fact("node.axis", "the split's axis (0 x, 1 y, 2 z)", [](I& i) { return double(i.chosen().axis); }),
      fact("node.position", "the split plane's position (world units)", [](I& i) { return double(i.chosen().position); }),
      fact("node.fraction", "the plane's position across the node, 0 to 1 (the chart's axis)",
           [](I& i) {
             const SahCandidate& c = i.chosen();
             const Bounds3& b = i.node_curve().info.box;
             return (double(c.position) - b.lo[c.axis]) / nonzero(double(b.hi[c.axis]) - b.lo[c.axis], "the extent");
           }),
      fact("node.n_below", "N_b: primitives below the plane", [](I& i) { return double(i.chosen().n_below); }),
      fact("node.n_above", "N_a: primitives above the plane", [](I& i) { return double(i.chosen().n_above); }),
      fact("node.p_below", "p_b = S_below / S_node (Crofton)",
           [](I& i) { return double(i.chosen().area_below) / nonzero(i.chosen().area_node, "the node's area"); }),
      fact("node.p_above", "p_a = S_above / S_node",
           [](I& i) { return double(i.chosen().area_above) / nonzero(i.chosen().area_node, "the node's area"); }),
      fact("node.size_x", "the node's extent along x", [](I& i) { const Bounds3& b = i.node_curve().info.box; return double(b.hi.x) - b.lo.x; }),
      fact("node.size_y", "the node's extent along y", [](I& i) { const Bounds3& b = i.node_curve().info.box; return double(b.hi.y) - b.lo.y; }),
      fact("node.size_z", "the node's extent along z", [](I& i) { const Bounds3& b = i.node_curve().info.box; return double(b.hi.z) - b.lo.z; }),
      fact("kd.t_i", "the kd-tree's cost of a primitive test", [](I& i) { return double(i.s.structure.kd.t_i); }),
      fact("kd.t_t", "the kd-tree's cost of a traversal step", [](I& i) { return double(i.s.structure.kd.t_t); }),
      fact("bvh.bins", "the binned BVH builder's bins per axis", [](I& i) { return double(i.s.structure.bvh.bins); }),
      fact("bvh.t_i", "the BVH's cost of a primitive test", [](I& i) { return double(i.s.structure.bvh.t_i); }),
      // The grid.
      fact("grid.nx", "cells along x", [](I& i) { return double(i.grid().resolution()[0]); }),
      fact("grid.ny", "cells along y", [](I& i) { return double(i.grid().resolution()[1]); }),
      fact("grid.nz", "cells along z", [](I& i) { return double(i.grid().resolution()[2]); }),
      fact("grid.cells", "nx ny nz", [](I& i) {
        const auto n = i.grid().resolution();
        return double(n[0]) * n[1] * n[2];
      }),
      fact("grid.density", "the density d of the rule d * cbrt(n)", [](I& i) { return double(i.s.structure.grid.density); }),
      fact("grid.references", "primitive references over all cells", [](I& i) { return double(i.grid().reference_count()); }),
      fact("grid.per_cell", "references per cell", [](I& i) {
        const auto n = i.grid().resolution();
        return double(i.grid().reference_count()) / (double(n[0]) * n[1] * n[2]);
      }),
      fact("grid.per_primitive", "cells per primitive (references / primitives)", [](I& i) {
        return double(i.grid().reference_count()) / nonzero(double(i.w.scene->geometry.size()), "the scene's primitives");
      }),
      // Any tree.
      fact("tree.nodes", "nodes of the built tree", [](I& i) { return i.tree().nodes; }),
      fact("tree.leaves", "leaves", [](I& i) { return i.tree().leaves; }),
      fact("tree.empty_leaves", "empty leaves", [](I& i) { return i.tree().empty_leaves; }),
      fact("tree.depth", "the deepest leaf's depth", [](I& i) { return i.tree().depth; }),
      fact("tree.references", "primitive references over all leaves", [](I& i) { return i.tree().references; }),
      fact("tree.per_primitive", "references per primitive", [](I& i) {
        return i.tree().references / nonzero(double(i.w.scene->geometry.size()), "the scene's primitives");
      }),
      fact("tree.sah_cost", "the tree's SAH cost (kd, BVH, BSP)", [](I& i) {
        const double c = i.tree().sah_cost;
        if (std::isnan(c)) I::fail("the octree has no SAH cost");
        return c;
      }),
      fact("bsp.axis_planes", "BSP inner nodes whose plane is an axis plane", [](I& i) { return double(i.bsp().inner_by_source[0]); }),
      fact("bsp.face_diagonal_planes", "BSP inner nodes on one of the 6 face diagonals", [](I& i) { return double(i.bsp().inner_by_source[1]); }),
      fact("bsp.body_diagonal_planes", "BSP inner nodes on one of the 4 body diagonals", [](I& i) { return double(i.bsp().inner_by_source[2]); }),
      fact("bsp.primitive_planes", "BSP inner nodes on a primitive's own plane", [](I& i) { return double(i.bsp().inner_by_source[3]); }),
      // The cost report (`raystep cost` on the step's scene, size and anti-aliasing).
      costly("cost.pixels", "m^2", [](I& i) { return double(i.cost_report().pixels); }),
      costly("cost.samples_per_pixel", "k^2: the anti-aliasing's largest samples per pixel",
             [](I& i) { return i.cost_report().samples_per_pixel; }),
      costly("cost.primitives", "n", [](I& i) { return double(i.cost_report().primitives); }),
      costly("cost.depth", "d", [](I& i) { return double(i.cost_report().depth); }),
      costly("cost.lights", "L", [](I& i) { return double(i.cost_report().lights); }),
      costly("cost.predicted", "the lecture's m^2 k^2 n 2^d", [](I& i) { return i.cost_report().predicted; }),
      costly("cost.bound", "m^2 k^2 n (2^(d+1) - 1)(1 + L)", [](I& i) { return i.cost_report().bound; }),
      fn("cost.tests", true, "a row's ray-primitive tests: cost.tests(\"LABEL\")",
         [](I& i, const std::string& a) { return double(i.cost_row(a).tests); }),
      fn("cost.tests_per_ray", true, "a row's tests per ray", [](I& i, const std::string& a) { return i.cost_row(a).tests_per_ray; }),
      fn("cost.rays_per_sample", true, "a row's rays per primary ray",
         [](I& i, const std::string& a) { return i.cost_row(a).rays_per_sample; }),
      fn("cost.rays", true, "a row's rays, all kinds", [](I& i, const std::string& a) {
        const RayCounts& r = i.cost_row(a).rays;
        return double(r.primary + r.shadow + r.reflected + r.refracted);
      }),
      fn("cost.cut", true, "a technique's cut of its factor: cost.cut(\"kd\"), cost.cut(\"adaptive ray termination\")",
         [](I& i, const std::string& a) { return i.cost_factor(a).cut(); }),
      fn("cost.before", true, "a technique's measure without it", [](I& i, const std::string& a) { return i.cost_factor(a).before; }),
      fn("cost.after", true, "a technique's measure with it", [](I& i, const std::string& a) { return i.cost_factor(a).after; }),
      // Crofton's theorem: random lines (random_lines.h) against the kd-tree's root box and its nodes.
      fact("crofton.box_predicted", "(S/4) / (pi R^2): the share of random lines through the root box's bounding sphere that meet the box, by Cauchy-Crofton",
           [](I& i) { return lines_meeting_box(i.kd().data().bounds, 0, 1).predicted; }),
      costly("crofton.box_lines", "the share of 100,000 random lines through the root box's bounding sphere that meet the box, measured",
             [](I& i) { return lines_meeting_box(i.kd().data().bounds, 100000, 1).measured; }),
      fn("crofton.predicted", false, "S_node / S_root of the kd node at a path: crofton.predicted(\"L\")",
         [](I& i, const std::string& a) {
           const KdTreeData& d = i.kd().data();
           return double(d.info[i.kd_node(a)].box.surface_area()) / nonzero(d.bounds.surface_area(), "the root's area");
         }),
      fn("crofton.lines", true, "the share of 100,000 random lines through the root that cross the node at a path",
         [](I& i, const std::string& a) { return i.entry(a).lines; }),
      fn("crofton.rays", true, "the share of the same lines, cast as rays, whose walk entered the node at a path",
         [](I& i, const std::string& a) { return i.entry(a).rays; }),
      // The bounding-volume report (`raystep bvol-report`, one ray per pixel of the scene's camera).
      fn("bvol.objects", true, "objects (one volume each): bvol.objects(\"bvol\")",
         [](I& i, const std::string& a) { return double(i.bvol_row(a).objects); }),
      fn("bvol.entered", true, "a kind's volumes entered per ray: bvol.entered(\"bvol-obb\")",
         [](I& i, const std::string& a) { return i.bvol_row(a).entered_per_ray; }),
      fn("bvol.in_vain", true, "a kind's volumes entered in vain per ray (false positives)",
         [](I& i, const std::string& a) { return i.bvol_row(a).false_positives_per_ray; }),
      fn("bvol.false_positive_rate", true, "a kind's false positives / volumes entered",
         [](I& i, const std::string& a) { return i.bvol_row(a).false_positive_rate; }),
      fn("bvol.tests", true, "a kind's primitive tests per ray", [](I& i, const std::string& a) { return i.bvol_row(a).prim_tests_per_ray; }),
      // The anti-aliasing report (`raystep aa-report` on the step's scene and size).
      fn("aa.rmse", true, "a method's RMSE against the reference: aa.rmse(\"jitter:4\")",
         [](I& i, const std::string& a) { return i.aa_row(a).rmse; }),
      fn("aa.max_error", true, "a method's largest pixel error against the reference: aa.max_error(\"jitter:4\")",
         [](I& i, const std::string& a) { return i.aa_row(a).max_error; }),
      fn("aa.rays", true, "a method's primary rays per pixel", [](I& i, const std::string& a) { return i.aa_row(a).rays_per_pixel; }),
      fn("aa.slope", true, "a method's fitted slope of log RMSE against log rays: aa.slope(\"jitter\")",
         [](I& i, const std::string& a) {
           for (const auto& [method, slope] : i.aa_rep().slopes)
             if (method == a) return slope;
           I::fail("the aa-report fits no slope for '" + a + "' (regular, jitter, random)");
         }),
  };
  return table;
}

const Fact* find_fact(const std::string& name) {
  for (const Fact& f : facts())
    if (f.info.name == name) return &f;
  return nullptr;
}

}  // namespace

const std::vector<LessonFactInfo>& lesson_fact_list() {
  static const std::vector<LessonFactInfo> list = [] {
    std::vector<LessonFactInfo> l;
    for (const Fact& f : facts()) l.push_back(f.info);
    return l;
  }();
  return list;
}

const LessonFactInfo* find_lesson_fact(const std::string& name) {
  const Fact* f = find_fact(name);
  return f ? &f->info : nullptr;
}

LessonFacts::LessonFacts(const StepWorld& world, const LessonState& state)
    : impl_(std::make_unique<Impl>(world, state)) {}
LessonFacts::~LessonFacts() = default;

double LessonFacts::value(const std::string& name) {
  auto it = impl_->values.find(name);
  if (it != impl_->values.end()) return it->second;
  const Fact* f = find_fact(name);
  if (!f || f->info.function) throw InputError("", 0, "'" + name + "' is no lesson fact");
  const double v = f->get(*impl_);
  impl_->values[name] = v;
  return v;
}

double LessonFacts::call(const std::string& name, const std::string& arg) {
  const std::string key = name + "(\"" + arg + "\")";
  auto it = impl_->values.find(key);
  if (it != impl_->values.end()) return it->second;
  const Fact* f = find_fact(name);
  if (!f || !f->info.function) throw InputError("", 0, "'" + name + "' is no lesson function");
  const double v = f->call(*impl_, arg);
  impl_->values[key] = v;
  return v;
}

}  // namespace raystep
