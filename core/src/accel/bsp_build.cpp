// General BSP tree construction (accel/bsp_build.h): per node, the k-DOP directions' candidate positions and
// a sample of the primitives' own planes, each weighed by the SAH with the children's polytope areas; the
// chosen plane then classifies the node's primitives exactly.
#include "raystep/accel/bsp_build.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <gmpxx.h>
#include <glm/geometric.hpp>

#include "raystep/accel/bsp_cell.h"
#include "raystep/util/error.h"

namespace raystep {

int bsp_plane_side(const BspPlane& plane, const glm::vec3& p) {
  // Each product of two floats is exact in double (24 + 24 significant bits); the three additions that
  // follow err by at most gamma(3) of the sum of magnitudes. Outside that bound the double's sign is right.
  const double a = double(plane.normal.x) * p.x, b = double(plane.normal.y) * p.y,
               c = double(plane.normal.z) * p.z;
  const double d = plane.offset;
  const double s = ((a + b) + c) - d;
  const double bound = std::ldexp(std::fabs(a) + std::fabs(b) + std::fabs(c) + std::fabs(d), -50);
  if (s > bound) return 1;
  if (s < -bound) return -1;
  if (!std::isfinite(s)) return 0;
  // With at most one product non-zero (an axis plane, a point on a coordinate plane) the sum is exact and the
  // one subtraction left keeps its sign (x - d rounds to zero only when x = d): the common case of a vertex
  // lying on an axis plane needs no rationals.
  if ((a != 0.0) + (b != 0.0) + (c != 0.0) <= 1) return (s > 0.0) - (s < 0.0);
  // Too close to call in double: the four exact terms summed as rationals.
  mpq_class e = mpq_class(a) + mpq_class(b) + mpq_class(c) - mpq_class(d);
  return sgn(e);
}

const char* bsp_plane_source_name(BspPlaneSource source) {
  switch (source) {
    case BspPlaneSource::axis:
      return "axis";
    case BspPlaneSource::face_diagonal:
      return "face_diagonal";
    case BspPlaneSource::body_diagonal:
      return "body_diagonal";
    case BspPlaneSource::primitive:
      return "primitive";
  }
  return "unknown";
}

const char* bsp_directions_name(BspDirections d) {
  switch (d) {
    case BspDirections::autopartition:
      return "autopartition";
    case BspDirections::kdop:
      return "kdop";
    case BspDirections::both:
      return "both";
  }
  return "unknown";
}

bool parse_bsp_directions(const std::string& text, BspDirections* d) {
  for (BspDirections c : {BspDirections::autopartition, BspDirections::kdop, BspDirections::both})
    if (text == bsp_directions_name(c)) {
      *d = c;
      return true;
    }
  return false;
}

const char* bsp_leaf_reason_name(BspLeafReason reason) {
  switch (reason) {
    case BspLeafReason::few_primitives:
      return "few_primitives";
    case BspLeafReason::max_depth:
      return "max_depth";
    case BspLeafReason::no_area:
      return "no_area";
    case BspLeafReason::no_cheaper_split:
      return "no_cheaper_split";
    case BspLeafReason::separates_nothing:
      return "separates_nothing";
    case BspLeafReason::budget:
      return "budget";
  }
  return "unknown";
}

namespace {
// The 13 k-DOP directions before normalisation, in the tie order: axes, face diagonals, body diagonals.
const float kKdop[kBspKdopDirections][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1}, {1, 1, 0},  {1, -1, 0},
                                            {1, 0, 1},  {1, 0, -1}, {0, 1, 1}, {0, 1, -1}, {1, 1, 1},
                                            {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
const char* const kKdopNames[kBspKdopDirections] = {"x",   "y",   "z",     "x+y",   "x-y",   "x+z",   "x-z",
                                                    "y+z", "y-z", "x+y+z", "x+y-z", "x-y+z", "-x+y+z"};
}  // namespace

glm::vec3 bsp_kdop_direction(int direction) {
  if (direction < 0 || direction >= kBspKdopDirections) return glm::vec3(0.f);
  const float* v = kKdop[direction];
  return glm::normalize(glm::vec3(v[0], v[1], v[2]));
}

const char* bsp_direction_name(int direction) {
  return direction >= 0 && direction < kBspKdopDirections ? kKdopNames[direction] : "own plane";
}

int bsp_max_depth(const BspOptions& options, size_t prim_count) {
  if (options.max_depth > 0) return std::min(options.max_depth, kBspMaxDepth);
  double n = double(std::max<size_t>(prim_count, 1));
  return std::min(kBspMaxDepth, std::max(8, int(std::lround(1.2 * std::log2(n)))));
}

namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, "bsp: " + what);
}

void validate(const Geometry& geometry, const BspOptions& o) {
  if (o.directions != BspDirections::autopartition && o.directions != BspDirections::kdop &&
      o.directions != BspDirections::both)
    fail("unknown directions");
  if (o.candidates < 1 || o.candidates > 4096) fail("candidates must be in 1..4096");
  if (!std::isfinite(o.t_i) || !(o.t_i > 0.f)) fail("t_i must be a finite number > 0");
  if (!std::isfinite(o.t_t) || !(o.t_t >= 0.f)) fail("t_t must be a finite number >= 0");
  if (o.max_depth < 0 || o.max_depth > kBspMaxDepth)
    fail("max_depth must be in 0.." + std::to_string(kBspMaxDepth) + " (0: automatic)");
  if (o.leaf_size < 1) fail("leaf_size must be at least 1");
  if (!std::isfinite(o.reference_budget) || !(o.reference_budget >= 1.f))
    fail("reference_budget must be a finite number >= 1");
  if (geometry.size() >= BspNode::kInner) fail("too many primitives");
  for (uint32_t id = 0; id < geometry.size(); ++id) {
    Bounds3 b = geometry.prim_bounds(id);
    if (!is_finite(b.lo) || !is_finite(b.hi)) fail("primitive " + std::to_string(id) + " is not finite");
  }
}

// The 13 k-DOP directions, unit length in float, in the tie order: axes, face diagonals, body diagonals; in
// the plane the four that are vertical planes (x, y, x+y, x-y). `index` is the direction's number.
struct Direction {
  glm::vec3 normal;
  BspPlaneSource source;
  int index;
};
std::vector<Direction> kdop_directions(SplitSpace space) {
  std::vector<Direction> out;
  for (int i = 0; i < kBspKdopDirections; ++i)
    if (!space.plane() || bsp_kdop_direction(i).z == 0.f)
      out.push_back({bsp_kdop_direction(i),
                     i < 3   ? BspPlaneSource::axis
                     : i < 9 ? BspPlaneSource::face_diagonal
                             : BspPlaneSource::body_diagonal,
                     i});
  return out;
}

// The floats a double vector rounds to, out of line: GCC 12.2's SLP vectorizer (-O2 and -O3, x86-64) drops
// the rounding of a pair of double(float(x)) round trips made in one function, so an own plane's normal,
// widened again for its extent and counts, was not the float normal the node stores (by up to 2e-8: the SAH
// inspector's test found it; /work/notes/gcc12-slp-float-roundtrip.cpp reproduces it in 6 lines).
[[gnu::noinline]] glm::vec3 round_to_float(const glm::dvec3& v) {
  return glm::vec3(v);
}

// The best candidate so far (what the builder needs; the rest is for the listener).
struct Candidate {
  BspPlane plane;
  BspPlaneSource source = BspPlaneSource::axis;
  uint32_t n_below = 0, n_above = 0;
  double cost = kInfinity;
  int direction = -1;
  uint32_t prim = UINT32_MAX;
  double cell_min = 0.0, cell_max = 0.0, area_below = 0.0, area_above = 0.0;
};

// The builder's recorders, as the kd-tree's (kdtree_build.h): the null one compiles every listener call away.
struct NullBspRecorder {
  static constexpr bool enabled = false;
};
struct ListenerBspRecorder {
  static constexpr bool enabled = true;
  BspBuildListener* listener;
};

template <class Recorder>
class Builder {
 public:
  Builder(const Geometry& g, const BspOptions& o, Recorder rec = {}) : geometry_(g), options_(o), rec_(rec) {
    max_depth_ = bsp_max_depth(o, g.size());
    double budget = std::ceil(double(o.reference_budget) * double(g.size()));
    budget_ = std::max(g.size(), size_t(std::min(budget, double(BspNode::kInner - 1))));
    if (o.directions != BspDirections::autopartition) directions_ = kdop_directions(g.split_space());
    // Every primitive as the points whose convex hull contains it: a triangle's vertices, a sphere's box.
    point_start_.push_back(0);
    for (uint32_t id = 0; id < g.size(); ++id) {
      if (g.type(id) == PrimType::triangle) {
        for (int k = 0; k < 3; ++k) points_.push_back(g.vertex(id, k));
      } else {
        Bounds3 b = g.prim_bounds(id);
        for (int c = 0; c < 8; ++c)
          points_.push_back(
              glm::vec3(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z));
      }
      point_start_.push_back(uint32_t(points_.size()));
    }
  }

  BspTreeData build() {
    tree_.bounds = geometry_.bounds();
    tree_.space = geometry_.split_space();
    std::vector<uint32_t> all(geometry_.size());
    for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    build_node(ConvexCell::box(tree_.bounds), -1, 0, budget_, std::move(all));
    tree_.nodes.shrink_to_fit();
    tree_.info.shrink_to_fit();
    tree_.prim_index.shrink_to_fit();
    return std::move(tree_);
  }

 private:
  // min and max of dot(n, point) over a primitive's points, in double.
  void project(uint32_t prim, const glm::dvec3& n, double d, double* lo, double* hi) const {
    double a = kInfinity, b = -kInfinity;
    for (uint32_t k = point_start_[prim]; k < point_start_[prim + 1]; ++k) {
      double s = glm::dot(n, glm::dvec3(points_[k])) - d;
      a = std::min(a, s);
      b = std::max(b, s);
    }
    *lo = a;
    *hi = b;
  }

  double cost(double area_below, double area_above, double area, uint32_t nb, uint32_t na) const {
    return double(options_.t_t) +
           double(options_.t_i) * (area_below / area * double(nb) + area_above / area * double(na));
  }

  // Weigh one candidate plane (with its counts) and keep it if strictly cheaper than the best. direction,
  // prim, clo and chi only describe it (the listener's).
  void offer(const ConvexCell& cell, double area, const BspPlane& plane, BspPlaneSource source, int direction,
             uint32_t prim, double clo, double chi, uint32_t nb, uint32_t na, Candidate* best) {
    // The two areas add up to at least the node's (the cap counts twice), so the cost is at least
    // t_t + t_i min(nb, na): skip the clipping when even that is no better.
    const bool bounded = cost(area, area, 2.0 * area, std::min(nb, na), std::min(nb, na)) >= best->cost;
    if constexpr (Recorder::enabled) {
      if (bounded && !recording_) return;  // a recorded node's curve has every candidate's cost
    } else {
      if (bounded) return;
    }
    double ab, aa;
    cell.split_measures(glm::dvec3(plane.normal), double(plane.offset), tree_.space, &ab, &aa);
    if (!(ab > 0.0 && aa > 0.0)) return;  // the plane does not cut the cell
    double c = cost(ab, aa, area, nb, na);
    if constexpr (Recorder::enabled) {
      if (recording_) {
        BspCandidate r;
        r.plane = plane;
        r.source = source;
        r.direction = direction;
        r.prim = prim;
        r.cell_min = clo;
        r.cell_max = chi;
        r.n_below = nb;
        r.n_above = na;
        r.area_below = ab;
        r.area_above = aa;
        r.area_node = area;
        r.cost = c;
        r.bounded = bounded;
        recorded_.push_back(r);
      }
    }
    if (!bounded && c < best->cost) {
      *best = Candidate{plane, source, nb, na, c, direction, prim, clo, chi, ab, aa};
      if constexpr (Recorder::enabled)
        if (recording_) best_index_ = int(recorded_.size()) - 1;
    }
  }

  // The candidates along a fixed direction: positions at the primitives' extents (all, or an even sample).
  void direction_candidates(const ConvexCell& cell, double area, int direction, const Direction& dir,
                            const std::vector<uint32_t>& prims, Candidate* best) {
    const glm::dvec3 n(dir.normal);
    const size_t N = prims.size();
    lo_.resize(N);
    hi_.resize(N);
    for (size_t i = 0; i < N; ++i) project(prims[i], n, 0.0, &lo_[i], &hi_[i]);
    double clo, chi;
    cell.extent(n, &clo, &chi);
    const size_t K = size_t(options_.candidates);
    pos_.clear();
    auto add = [&](double s) {
      float f = float(s);  // the plane's offset is a float: weigh the plane that would be stored
      if (double(f) > clo && double(f) < chi) pos_.push_back(f);
    };
    if (2 * N <= K) {
      for (size_t i = 0; i < N; ++i) {
        add(lo_[i]);
        add(hi_[i]);
      }
    } else {
      const size_t half = std::max<size_t>(1, K / 2);
      for (size_t j = 0; j < half; ++j) {
        size_t i = (2 * j + 1) * N / (2 * half);
        add(lo_[i]);
        add(hi_[i]);
      }
    }
    std::sort(pos_.begin(), pos_.end());
    pos_.erase(std::unique(pos_.begin(), pos_.end()), pos_.end());
    const size_t P = pos_.size();
    if (P == 0) return;
    // Counts at every position by histograms: below where some point is below (lo < s), above where some
    // point is above (hi > s); planar ones (lo = hi = s) below.
    hist_below_.assign(P + 1, 0);
    hist_above_.assign(P + 1, 0);
    planar_.assign(P, 0);
    for (size_t i = 0; i < N; ++i) {
      size_t jb = size_t(std::upper_bound(pos_.begin(), pos_.end(), lo_[i]) - pos_.begin());
      ++hist_below_[jb];
      size_t ja = size_t(std::lower_bound(pos_.begin(), pos_.end(), hi_[i]) - pos_.begin());
      ++hist_above_[ja];
      if (lo_[i] == hi_[i] && ja < P && pos_[ja] == hi_[i]) ++planar_[ja];
    }
    uint32_t below = 0, above = uint32_t(N);
    for (size_t k = 0; k < P; ++k) {
      below += hist_below_[k];
      above -= hist_above_[k];
      offer(cell, area, BspPlane{dir.normal, float(pos_[k])}, dir.source, direction, UINT32_MAX, clo, chi,
            below + planar_[k], above, best);
    }
  }

  // The primitives' own planes: an even sample of the node's triangles.
  void primitive_candidates(const ConvexCell& cell, double area, const std::vector<uint32_t>& prims,
                            Candidate* best) {
    const size_t N = prims.size();
    // Beside the 13 directions a quarter as many primitive planes: the SAH, greedy, takes the planes through
    // single triangles too eagerly and builds worse trees with more (bench/README.md, "BSP tree").
    const int planes = options_.directions == BspDirections::autopartition
                           ? options_.candidates
                           : std::max(1, options_.candidates / 4);
    const size_t K = std::min(N, size_t(planes));
    for (size_t j = 0; j < K; ++j) {
      uint32_t src = prims[(2 * j + 1) * N / (2 * K)];
      if (geometry_.type(src) != PrimType::triangle) continue;
      glm::dvec3 p0(geometry_.vertex(src, 0)), p1(geometry_.vertex(src, 1)), p2(geometry_.vertex(src, 2));
      glm::dvec3 nd = glm::cross(p1 - p0, p2 - p0);
      double len = glm::length(nd);
      if (!(len > 0.0) || !std::isfinite(len)) continue;  // a degenerate triangle has no plane
      if (tree_.space.plane() && nd.z != 0.0) continue;   // in the plane only a wall's plane cuts it
      BspPlane plane;
      plane.normal = round_to_float(nd / len);
      plane.offset = float(glm::dot(glm::dvec3(plane.normal), (p0 + p1 + p2) / 3.0));
      const glm::dvec3 n(plane.normal);
      double clo, chi;
      cell.extent(n, &clo, &chi);
      if (!(double(plane.offset) > clo && double(plane.offset) < chi)) continue;
      uint32_t nb = 0, na = 0;
      for (uint32_t prim : prims) {
        double lo, hi;
        project(prim, n, double(plane.offset), &lo, &hi);
        bool above = hi > 0.0;
        nb += lo < 0.0 || !above;
        na += above;
      }
      offer(cell, area, plane, BspPlaneSource::primitive, -1, src, clo, chi, nb, na, best);
    }
  }

  uint32_t add_node(const ConvexCell& cell, double area, int32_t parent, int32_t depth) {
    if (tree_.nodes.size() >= BspNode::kInner - 1) fail("too many nodes");
    tree_.nodes.push_back(BspNode{});
    BspNodeInfo info;
    info.box = cell.bounds();
    info.area = float(area);
    info.parent = parent;
    info.depth = depth;
    tree_.info.push_back(info);
    return uint32_t(tree_.nodes.size() - 1);
  }

  void make_leaf(uint32_t node, std::vector<uint32_t>& prims) {
    std::sort(prims.begin(), prims.end());
    BspNode& n = tree_.nodes[node];
    n.child_or_first = uint32_t(tree_.prim_index.size());
    n.count = uint32_t(prims.size());
    tree_.prim_index.insert(tree_.prim_index.end(), prims.begin(), prims.end());
    tree_.info[node].cost = options_.t_i * float(prims.size());
  }

  // A leaf, told to the listener with its reason (after the node's candidates, if it searched).
  void leaf(uint32_t node, std::vector<uint32_t>& prims, BspLeafReason reason) {
    const uint32_t n = uint32_t(prims.size());
    if constexpr (Recorder::enabled) report_candidates(node, -1);
    make_leaf(node, prims);
    if constexpr (Recorder::enabled)
      rec_.listener->leaf_made(node, tree_.info[node], n, tree_.info[node].cost, reason);
  }

  // The recorded node's candidates, in the builder's order, `chosen` marked (-1: none).
  void report_candidates(uint32_t node, int chosen) {
    if (!recording_) return;
    for (size_t i = 0; i < recorded_.size(); ++i) {
      recorded_[i].chosen = int(i) == chosen;
      rec_.listener->candidate(node, recorded_[i]);
    }
    recorded_.clear();
    recording_ = false;
  }

  void build_node(const ConvexCell& cell, int32_t parent, int32_t depth, size_t budget,
                  std::vector<uint32_t> prims) {
    const double area = cell.measure(tree_.space);
    const uint32_t node = add_node(cell, area, parent, depth);
    const uint32_t N = uint32_t(prims.size());
    const double leaf_cost = double(options_.t_i) * N;
    if constexpr (Recorder::enabled) {
      if (rec_.listener->done()) return make_leaf(node, prims);  // the rest is not wanted
      recording_ = rec_.listener->wants_candidates(node);
      recorded_.clear();
      best_index_ = -1;
    }
    if (N <= uint32_t(options_.leaf_size)) return leaf(node, prims, BspLeafReason::few_primitives);
    if (depth >= max_depth_) return leaf(node, prims, BspLeafReason::max_depth);
    if (!(area > 0.0)) return leaf(node, prims, BspLeafReason::no_area);

    Candidate best;
    best.cost = leaf_cost;  // a split must be strictly cheaper than the leaf
    for (size_t i = 0; i < directions_.size(); ++i)
      direction_candidates(cell, area, directions_[i].index, directions_[i], prims, &best);
    if (options_.directions != BspDirections::kdop) primitive_candidates(cell, area, prims, &best);
    if (!(best.cost < leaf_cost)) return leaf(node, prims, BspLeafReason::no_cheaper_split);

    // The chosen plane classifies every primitive exactly (bsp_build.h): no point of one may be lost.
    std::vector<uint32_t> below, above;
    for (uint32_t prim : prims) {
      bool b = false, a = false;
      for (uint32_t k = point_start_[prim]; k < point_start_[prim + 1] && !(a && b); ++k) {
        int s = bsp_plane_side(best.plane, points_[k]);
        b |= s < 0;
        a |= s > 0;
      }
      if (b || !a) below.push_back(prim);
      if (a) above.push_back(prim);
    }
    if (below.size() == N && above.size() == N) return leaf(node, prims, BspLeafReason::separates_nothing);
    if (below.size() + above.size() > budget) return leaf(node, prims, BspLeafReason::budget);

    tree_.info[node].cost = float(best.cost);
    tree_.info[node].source = best.source;
    tree_.nodes[node].plane = best.plane;
    if constexpr (Recorder::enabled) {
      BspCandidate chosen;
      chosen.plane = best.plane;
      chosen.source = best.source;
      chosen.direction = best.direction;
      chosen.prim = best.prim;
      chosen.cell_min = best.cell_min;
      chosen.cell_max = best.cell_max;
      chosen.n_below = best.n_below;
      chosen.n_above = best.n_above;
      chosen.area_below = best.area_below;
      chosen.area_above = best.area_above;
      chosen.area_node = area;
      chosen.cost = best.cost;
      chosen.chosen = true;
      report_candidates(node, best_index_);
      rec_.listener->split(node, tree_.info[node], N, chosen, uint32_t(below.size()), uint32_t(above.size()),
                           float(leaf_cost));
    }
    ConvexCell cell_below, cell_above;
    cell.split(glm::dvec3(best.plane.normal), double(best.plane.offset), &cell_below, &cell_above);
    prims.clear();
    prims.shrink_to_fit();
    // The budget shared as the kd-tree shares it (kdtree_build_common.h, build_children).
    const uint32_t nb = uint32_t(below.size()), na = uint32_t(above.size());
    const size_t refs_before = tree_.prim_index.size();
    build_node(cell_below, int32_t(node), depth + 1, size_t(uint64_t(budget) * nb / (uint64_t(nb) + na)),
               std::move(below));
    const size_t used_below = tree_.prim_index.size() - refs_before;
    tree_.nodes[node].child_or_first = uint32_t(tree_.nodes.size());
    build_node(cell_above, int32_t(node), depth + 1, budget - used_below, std::move(above));
  }

  const Geometry& geometry_;
  BspOptions options_;
  Recorder rec_;
  // The node being recorded (the listener wants its candidates): every candidate, and the best one's index.
  bool recording_ = false;
  std::vector<BspCandidate> recorded_;
  int best_index_ = -1;
  int max_depth_ = 0;
  size_t budget_ = 0;
  std::vector<Direction> directions_;
  std::vector<glm::vec3> points_;
  std::vector<uint32_t> point_start_;
  BspTreeData tree_;
  // Scratch arrays of the candidate search, reused from node to node.
  std::vector<double> lo_, hi_, pos_;
  std::vector<uint32_t> hist_below_, hist_above_, planar_;
};

}  // namespace

BspTreeData build_bsp(const Geometry& geometry, const BspOptions& options) {
  validate(geometry, options);
  return Builder<NullBspRecorder>(geometry, options).build();
}

BspTreeData build_bsp(const Geometry& geometry, const BspOptions& options, BspBuildListener& listener) {
  validate(geometry, options);
  return Builder<ListenerBspRecorder>(geometry, options, ListenerBspRecorder{&listener}).build();
}

BspTreeStats bsp_tree_stats(const BspTreeData& tree, const BspOptions& options) {
  BspTreeStats s;
  s.nodes = tree.nodes.size();
  s.references = tree.prim_index.size();
  const double root_area = tree.info.empty() ? 0.0 : double(tree.info[0].area);
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const BspNode& node = tree.nodes[i];
    const BspNodeInfo& info = tree.info[i];
    s.max_depth = std::max(s.max_depth, int(info.depth));
    double p = root_area > 0.0 ? double(info.area) / root_area : 1.0;
    if (node.is_leaf()) {
      ++s.leaves;
      if (node.prim_count() == 0) ++s.empty_leaves;
      s.max_leaf_prims = std::max<size_t>(s.max_leaf_prims, node.prim_count());
      s.sah_cost += p * double(options.t_i) * double(node.prim_count());
    } else {
      ++s.inner_by_source[int(info.source)];
      s.sah_cost += p * double(options.t_t);
    }
  }
  return s;
}

}  // namespace raystep
