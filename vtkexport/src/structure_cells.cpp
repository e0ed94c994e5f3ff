// Each structure's cells for the export: one describe_* function per structure and one row in kStructures.
// A new structure (octree, BSP tree) adds its function and its row here; the rest of the export works from
// the CellSet it fills. Arrays common to the trees: node, parent, depth, leaf, primitives, cost, split_axis
// (docs/vtk-export.md lists them per structure).
#include "raystep/vtk_export/structure_cells.h"

#include <algorithm>
#include <limits>
#include <map>
#include <unordered_map>

#include "bsp_cells.h"
#include "raystep/accel/bsp.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/util/error.h"

namespace raystep::vtk_export {

namespace {

constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

// The deepest level d such that the nodes of depth 0..d number at most max_cells (-1: not even the root).
int depth_cut(const std::vector<int>& depths, size_t max_cells) {
  int max_depth = 0;
  for (int d : depths) max_depth = std::max(max_depth, d);
  std::vector<size_t> per_depth(size_t(max_depth) + 1, 0);
  for (int d : depths) ++per_depth[size_t(d)];
  size_t total = 0;
  for (int d = 0; d <= max_depth; ++d) {
    total += per_depth[size_t(d)];
    if (total > max_cells) return d - 1;
  }
  return max_depth;
}

// The note for a tree cut at depth `cut`.
std::string depth_note(int cut, const std::vector<int>& depths, size_t written, size_t max_cells) {
  int max_depth = 0;
  for (int d : depths) max_depth = std::max(max_depth, d);
  if (cut >= max_depth) return "";
  return "nodes of depth 0.." + std::to_string(cut) + " only (" + std::to_string(written) + " of " +
         std::to_string(depths.size()) + " nodes, the tree is " + std::to_string(max_depth) +
         " deep; --max-cells " + std::to_string(max_cells) + ")";
}

// The columns every tree has, for the cell just added.
void set_tree_columns(CellSet& cs, size_t id, double parent, int depth, bool leaf, double primitives) {
  cs.set("node", double(id), true);
  cs.set("parent", parent, true);
  cs.set("depth", depth, true);
  cs.set("leaf", leaf, true);
  cs.set("primitives", primitives, true);
}

// The nodes of depth 0..cut, the most that fit in max_cells, in id order: add_node(id) adds each one's cell
// and columns; the note says what was left out.
template <class AddNode>
void add_tree_nodes(const std::vector<int>& depths, size_t max_cells, StructureCells* out, AddNode add_node) {
  const int cut = depth_cut(depths, max_cells);
  for (size_t id = 0; id < depths.size(); ++id)
    if (depths[id] <= cut) add_node(id);
  out->note = depth_note(cut, depths, out->cells.size(), max_cells);
}

// An inner node's primitive count in a tree that puts a primitive into every leaf it overlaps (kd-tree, BSP
// tree): the distinct primitives of its leaves, merged bottom-up (preorder ids put every child after its
// parent, the one below at id + 1). first_prim(node) is where a leaf's run starts in prim_index.
template <class Node, class FirstPrim>
std::vector<uint32_t> distinct_primitives(const std::vector<Node>& nodes,
                                          const std::vector<uint32_t>& prim_index, FirstPrim first_prim) {
  const size_t n = nodes.size();
  std::vector<uint32_t> prims(n, 0);
  std::vector<std::vector<uint32_t>> sets(n);
  for (size_t id = n; id-- > 0;) {
    const Node& node = nodes[id];
    if (node.is_leaf()) {
      sets[id].assign(prim_index.begin() + first_prim(node),
                      prim_index.begin() + first_prim(node) + node.prim_count());
    } else {
      std::vector<uint32_t>& below = sets[id + 1];
      std::vector<uint32_t>& above = sets[node.above_child()];
      std::set_union(below.begin(), below.end(), above.begin(), above.end(), std::back_inserter(sets[id]));
      std::vector<uint32_t>().swap(below);
      std::vector<uint32_t>().swap(above);
    }
    prims[id] = uint32_t(sets[id].size());
  }
  return prims;
}

// ---- uniform grid: every cell with its primitive count; when they are too many, the occupied ones ----

bool describe_grid(const Accelerator& accel, size_t max_cells, StructureCells* out) {
  auto* grid = dynamic_cast<const UniformGrid*>(&accel);
  if (!grid || !out) return grid != nullptr;
  const std::array<int, 3> n = grid->resolution();
  const size_t cells = size_t(n[0]) * size_t(n[1]) * size_t(n[2]);
  out->total = cells;
  if (grid->empty()) return true;
  auto count = [&](int i, int j, int k) {
    const size_t id = grid->cell_id(i, j, k);
    return grid->cell_start(id + 1) - grid->cell_start(id);
  };
  // The whole lattice when it fits (empty space is part of the lesson: the walk crosses it); else the
  // occupied cells; else cells merged into blocks of f x f x f (f = 2, 4, ...) until the occupied blocks fit.
  const bool every_cell = cells <= max_cells;
  int f = 1;
  size_t occupied = 0;
  for (size_t id = 0; id < cells; ++id) occupied += grid->occupied(id);
  std::vector<uint32_t> sums;
  std::array<int, 3> b = n;
  while (occupied > max_cells) {
    f *= 2;
    for (int a = 0; a < 3; ++a) b[a] = (n[a] + f - 1) / f;
    sums.assign(size_t(b[0]) * size_t(b[1]) * size_t(b[2]), 0);
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
          sums[(size_t(k / f) * b[1] + size_t(j / f)) * b[0] + size_t(i / f)] += count(i, j, k);
    occupied = size_t(std::count_if(sums.begin(), sums.end(), [](uint32_t s) { return s > 0; }));
  }
  CellSet& cs = out->cells;
  for (int k = 0; k < b[2]; ++k)
    for (int j = 0; j < b[1]; ++j)
      for (int i = 0; i < b[0]; ++i) {
        const uint32_t prims =
            f == 1 ? count(i, j, k) : sums[(size_t(k) * b[1] + size_t(j)) * b[0] + size_t(i)];
        if (prims == 0 && !every_cell) continue;
        Bounds3 box = grid->cell_bounds(i * f, j * f, k * f);
        box.extend(grid->cell_bounds(std::min((i + 1) * f, n[0]) - 1, std::min((j + 1) * f, n[1]) - 1,
                                     std::min((k + 1) * f, n[2]) - 1));
        cs.add_box(box);
        cs.set("i", i * f, true);
        cs.set("j", j * f, true);
        cs.set("k", k * f, true);
        cs.set("primitives", prims, true);
        cs.set("block", f, true);
      }
  if (f == 1 && !every_cell)
    out->note = "the " + std::to_string(cs.size()) +
                " occupied cells only, not the empty ones (--max-cells " + std::to_string(max_cells) + ")";
  if (f > 1)
    out->note = "occupied blocks of " + std::to_string(f) + "x" + std::to_string(f) + "x" +
                std::to_string(f) + " cells (their primitives summed), not single cells (--max-cells " +
                std::to_string(max_cells) + ")";
  return true;
}

// ---- kd-tree: every node's cell, its split plane and cost ----

bool describe_kdtree(const Accelerator& accel, size_t max_cells, StructureCells* out) {
  auto* kd = dynamic_cast<const KdTree*>(&accel);
  if (!kd || !out) return kd != nullptr;
  const KdTreeData& t = kd->data();
  const size_t n = t.nodes.size();
  out->total = n;
  const std::vector<uint32_t> prims =
      distinct_primitives(t.nodes, t.prim_index, [](const KdNode& node) { return node.first_prim; });
  std::vector<int> depths(n);
  for (size_t id = 0; id < n; ++id) depths[id] = t.info[id].depth;
  add_tree_nodes(depths, max_cells, out, [&](size_t id) {
    const KdNode& node = t.nodes[id];
    const KdNodeInfo& info = t.info[id];
    out->cells.add_box(info.box);
    set_tree_columns(out->cells, id, info.parent, info.depth, node.is_leaf(), prims[id]);
    out->cells.set("cost", info.cost, false);
    out->cells.set("split_axis", node.is_leaf() ? -1 : node.axis(), true);
    out->cells.set("split_position", node.is_leaf() ? kUnknown : double(node.split), false);
  });
  return true;
}

// ---- binary BVH (bvh, bvh-sweep, bvh-median): every node's tight box and cost ----

bool describe_bvh(const Accelerator& accel, size_t max_cells, StructureCells* out) {
  auto* bvh = dynamic_cast<const Bvh*>(&accel);
  if (!bvh || !out) return bvh != nullptr;
  const BvhData& t = bvh->data();
  const size_t n = t.nodes.size();
  out->total = n;
  std::vector<int> depths(n);
  for (size_t id = 0; id < n; ++id) depths[id] = t.info[id].depth;
  add_tree_nodes(depths, max_cells, out, [&](size_t id) {
    const BvhNode& node = t.nodes[id];
    const BvhNodeInfo& info = t.info[id];
    out->cells.add_box(node.box);
    set_tree_columns(out->cells, id, info.parent, info.depth, node.is_leaf(), info.prims);
    out->cells.set("cost", info.cost, false);
    out->cells.set("split_axis", node.is_leaf() ? -1 : node.axis(), true);
  });
  return true;
}

// ---- wide BVH (bvh4, bvh8): the collapsed nodes as traces name them; the collapse keeps no cost ----

bool describe_wide_bvh(const Accelerator& accel, size_t max_cells, StructureCells* out) {
  auto* wide = dynamic_cast<const WideBvh*>(&accel);
  if (!wide || !out) return wide != nullptr;
  const WideBvhView view = wide->describe();
  const size_t n = view.nodes.size();
  out->total = n;
  // Primitives under each node, children first (preorder ids: a child after its parent).
  std::vector<uint32_t> prims(n, 0);
  for (size_t id = n; id-- > 0;) {
    const WideBvhView::Node& node = view.nodes[id];
    prims[id] = uint32_t(node.prims.size());
    for (int32_t c : node.children) prims[id] += prims[size_t(c)];
  }
  std::vector<int> depths(n);
  for (size_t id = 0; id < n; ++id) depths[id] = view.nodes[id].depth;
  add_tree_nodes(depths, max_cells, out, [&](size_t id) {
    const WideBvhView::Node& node = view.nodes[id];
    out->cells.add_box(node.box);
    set_tree_columns(out->cells, id, node.parent, node.depth, node.leaf, prims[id]);
    out->cells.set("children", double(node.children.size()), true);
  });
  return true;
}

// ---- octree: every node's cubic cell; an inner node has 8 children, a leaf says why it was not split ----

bool describe_octree(const Accelerator& accel, size_t max_cells, StructureCells* out) {
  auto* octree = dynamic_cast<const Octree*>(&accel);
  if (!octree || !out) return octree != nullptr;
  const OctreeData& t = octree->data();
  const size_t n = t.nodes.size();
  out->total = n;
  std::vector<int> depths(n);
  for (size_t id = 0; id < n; ++id) depths[id] = t.info[id].depth;
  add_tree_nodes(depths, max_cells, out, [&](size_t id) {
    const OctreeNode& node = t.nodes[id];
    const OctreeNodeInfo& info = t.info[id];
    out->cells.add_box(info.box);
    // The primitives overlapping the cell (for an inner node, those it was split with: its leaves' union).
    set_tree_columns(out->cells, id, info.parent, info.depth, node.is_leaf(),
                     node.is_leaf() ? node.prim_count() : info.prims);
    out->cells.set("children", node.is_leaf() ? 0 : 8, true);
    out->cells.set("leaf_reason", node.is_leaf() ? int(info.reason) : -1, true);
  });
  return true;
}

// ---- general BSP tree: every node's convex cell (a VTK polyhedron), its plane, and that plane's polygon
// ----

bool describe_bsp(const Accelerator& accel, size_t max_cells, StructureCells* out) {
  auto* bsp = dynamic_cast<const BspTree*>(&accel);
  if (!bsp || !out) return bsp != nullptr;
  const BspTreeData& t = bsp->data();
  const size_t n = t.nodes.size();
  out->total = n;
  // Primitive counts as for the kd-tree: an inner node's are the distinct primitives of its leaves.
  const std::vector<uint32_t> prims =
      distinct_primitives(t.nodes, t.prim_index, [](const BspNode& node) { return node.first_prim(); });
  std::vector<int> depths(n);
  for (size_t id = 0; id < n; ++id) depths[id] = t.info[id].depth;
  const int cut = depth_cut(depths, max_cells);
  CellSet& cs = out->cells;
  if (n == 0 || cut < 0) {
    out->note = depth_note(cut, depths, 0, max_cells);
    return true;
  }
  // The cells are not stored: each is its parent's cut by the parent's plane, made walking the preorder with
  // a stack (the child below first), so that only the pending cells of one path are held at a time.
  struct Pending {
    uint32_t id;
    raystep::ConvexCell cell;
  };
  std::vector<Pending> stack;
  stack.push_back({0, raystep::ConvexCell::box(t.bounds)});
  size_t empty = 0, written = 0;
  while (!stack.empty()) {
    Pending p = std::move(stack.back());
    stack.pop_back();
    const BspNode& node = t.nodes[p.id];
    const BspNodeInfo& info = t.info[p.id];
    ++written;
    vtk_export::ConvexCell polytope = export_polytope(p.cell);
    if (polytope.faces.size() < 4) {
      // A plane that only grazes its parent's cell (within the cell's rounding tolerance) leaves all of it
      // on one side and nothing on the other, or a sliver too thin for floats: the builder keeps such a
      // node, but there is nothing to draw. Its children are empty or slivers too.
      ++empty;
      if (!node.is_leaf() && info.depth < cut) {
        raystep::ConvexCell below, above;
        p.cell.split(glm::dvec3(node.plane.normal), double(node.plane.offset), &below, &above);
        stack.push_back({node.above_child(), std::move(above)});
        stack.push_back({p.id + 1, std::move(below)});
      }
      continue;
    }
    cs.add_polytope(std::move(polytope));
    set_tree_columns(cs, p.id, info.parent, info.depth, node.is_leaf(), prims[p.id]);
    cs.set("cost", info.cost, false);
    cs.set("area", info.area, false);
    const bool inner = !node.is_leaf();
    cs.set("plane_source", inner ? int(info.source) : -1, true);
    cs.set("normal_x", inner ? double(node.plane.normal.x) : kUnknown, false);
    cs.set("normal_y", inner ? double(node.plane.normal.y) : kUnknown, false);
    cs.set("normal_z", inner ? double(node.plane.normal.z) : kUnknown, false);
    cs.set("offset", inner ? double(node.plane.offset) : kUnknown, false);
    if (!inner) continue;
    const glm::dvec3 normal(node.plane.normal);
    raystep::ConvexCell below, above;
    p.cell.split(normal, double(node.plane.offset), &below, &above);
    PlanePolygon polygon{plane_polygon(below, normal, double(node.plane.offset)), int32_t(p.id), info.depth};
    if (polygon.corners.size() >= 3) out->planes.push_back(std::move(polygon));
    if (info.depth >= cut) continue;
    stack.push_back({node.above_child(), std::move(above)});
    stack.push_back({p.id + 1, std::move(below)});
  }
  out->note = depth_note(cut, depths, written, max_cells);
  if (empty > 0)
    out->note += (out->note.empty() ? "" : "; ") + std::to_string(empty) +
                 " nodes with an empty cell or one too thin for floats (a plane that only grazes its "
                 "parent's cell) not drawn";
  return true;
}

// describe(accel, max_cells, out): false if accel is not this row's structure; with out null, only that test.
struct StructureRow {
  const char* names;
  bool (*describe)(const Accelerator&, size_t, StructureCells*);
};
const StructureRow kStructures[] = {
    {"grid", describe_grid},
    {"kd, kd-median", describe_kdtree},
    {"bvh, bvh-sweep, bvh-median", describe_bvh},
    {"bvh4, bvh8", describe_wide_bvh},
    {"octree", describe_octree},
    {"bsp", describe_bsp},
};

}  // namespace

bool exports_structure(const Accelerator& accel) {
  for (const StructureRow& row : kStructures)
    if (row.describe(accel, 0, nullptr)) return true;
  return false;
}

std::string exported_structure_names() {
  std::string s;
  for (const StructureRow& row : kStructures) s += (s.empty() ? "" : ", ") + std::string(row.names);
  return s;
}

StructureCells structure_cells(const Accelerator& accel, size_t max_cells) {
  if (max_cells == 0) throw InputError("", 0, "--max-cells must be at least 1");
  StructureCells out;
  out.kind = accel.name();
  for (const StructureRow& row : kStructures)
    if (row.describe(accel, max_cells, &out)) {
      out.cells.finish();
      return out;
    }
  throw InputError(
      "", 0, "the " + accel.name() + " structure has no VTK export (" + exported_structure_names() + ")");
}

StructureCells trace_structure_cells(const Trace& trace) {
  StructureCells out;
  out.kind = trace.structure.kind;
  CellSet& cs = out.cells;
  for (const TraceCell& c : trace.cells) {
    cs.add_box(c.box);
    cs.set("i", c.cell[0], true);
    cs.set("j", c.cell[1], true);
    cs.set("k", c.cell[2], true);
  }
  // The BVHs' and the octree's nodes carry their children, the kd-tree's their split plane, the BSP tree's
  // their plane of any direction (TraceNode in trace_file.h). A BSP node is drawn as its convex cell, rebuilt
  // from the root box and its ancestors' planes.
  const bool kd = trace.structure.kind.rfind("kd", 0) == 0;
  const bool bsp = trace.structure.kind == "bsp";
  const std::unordered_map<int32_t, raystep::ConvexCell> bsp_cells =
      bsp ? bsp_trace_cells(trace) : std::unordered_map<int32_t, raystep::ConvexCell>{};
  size_t empty = 0;
  for (const TraceNode& node : trace.nodes) {
    if (bsp) {
      vtk_export::ConvexCell polytope = export_polytope(bsp_cells.at(node.id));
      if (polytope.faces.size() < 4) {
        ++empty;  // nothing to draw (see describe_bsp)
        continue;
      }
      cs.add_polytope(std::move(polytope));
    } else {
      cs.add_box(node.box);
    }
    cs.set("node", node.id, true);
    cs.set("parent", node.parent, true);
    cs.set("depth", node.depth, true);
    cs.set("leaf", node.leaf, true);
    if (node.leaf) cs.set("primitives", double(node.prims.size()), true);
    if (bsp) {
      const bool plane = !node.leaf && node.has_plane;
      cs.set("normal_x", plane ? double(node.normal.x) : kUnknown, false);
      cs.set("normal_y", plane ? double(node.normal.y) : kUnknown, false);
      cs.set("normal_z", plane ? double(node.normal.z) : kUnknown, false);
      cs.set("offset", plane ? double(node.offset) : kUnknown, false);
      if (plane) {
        raystep::ConvexCell below, above;
        const glm::dvec3 normal(node.normal);
        bsp_cells.at(node.id).split(normal, double(node.offset), &below, &above);
        PlanePolygon polygon{plane_polygon(below, normal, double(node.offset)), node.id, node.depth};
        if (polygon.corners.size() >= 3) out.planes.push_back(std::move(polygon));
      }
      continue;
    }
    cs.set("split_axis", node.leaf ? -1 : node.axis, true);
    if (kd) cs.set("split_position", node.leaf ? kUnknown : double(node.split), false);
    if (!kd) cs.set("children", double(node.children.size()), true);
  }
  cs.finish();
  out.total = cs.size();
  if (!trace.nodes.empty() || !trace.cells.empty())
    out.note =
        "the " + std::to_string(cs.size()) + " cells or nodes the trace names, not the whole structure";
  if (empty > 0)
    out.note +=
        "; " + std::to_string(empty) + " named nodes with an empty cell or one too thin for floats not drawn";
  return out;
}

}  // namespace raystep::vtk_export
