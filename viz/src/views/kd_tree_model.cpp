#include "views/kd_tree_model.h"

#include <algorithm>

#include "app/session.h"

#include "raystep/replay/replay_state.h"
#include "raystep/replay/octree_choice.h"

namespace raystep::viz {

std::string kdNodePath(const KdTreeData& tree, uint32_t node) {
  std::string path;
  for (int32_t n = int32_t(node); n > 0 && size_t(n) < tree.info.size();) {
    int32_t p = tree.info[size_t(n)].parent;
    if (p < 0) break;
    path += n == p + 1 ? 'L' : 'R';
    n = p;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

int kdLeafContaining(const KdTreeData& tree, const glm::vec3& p) {
  if (tree.nodes.empty()) return -1;
  const Bounds3& b = tree.bounds;
  for (int a = 0; a < 3; ++a)
    if (!(p[a] >= b.lo[a] && p[a] <= b.hi[a])) return -1;
  uint32_t n = 0;
  // Down the tree by the split planes, as the traversal's point location would.
  while (!tree.nodes[n].is_leaf()) {
    const KdNode& node = tree.nodes[n];
    n = p[node.axis()] < node.split ? n + 1 : node.above_child();
  }
  return int(n);
}

std::string bvhNodePath(const BvhData& bvh, uint32_t node) {
  std::string path;
  for (int32_t n = int32_t(node); n > 0 && size_t(n) < bvh.info.size();) {
    int32_t p = bvh.info[size_t(n)].parent;
    if (p < 0) break;
    path += n == p + 1 ? 'L' : 'R';
    n = p;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

namespace {

class KdShape final : public TreeShape {
 public:
  explicit KdShape(const KdTreeData& t) : t_(t) {}
  const char* name() const override { return "kd-tree"; }
  size_t size() const override { return t_.nodes.size(); }
  int32_t parent(uint32_t n) const override { return t_.info[n].parent; }
  int32_t depth(uint32_t n) const override { return t_.info[n].depth; }
  bool leaf(uint32_t n) const override { return t_.nodes[n].is_leaf(); }
  uint32_t child(uint32_t n, int row) const override { return row == 0 ? n + 1 : t_.nodes[n].above_child(); }
  QString what(uint32_t id) const override {
    const KdNode& n = t_.nodes[id];
    if (n.is_leaf())
      return n.prim_count() == 0 ? QObject::tr("leaf, empty")
                                 : QObject::tr("leaf, %n primitive(s)", "", int(n.prim_count()));
    return QObject::tr("split %1 = %2").arg(replay::axis_name(n.axis())).arg(double(n.split), 0, 'g', 5);
  }
  QString whatHeader() const override { return QObject::tr("split or leaf"); }
  float cost(uint32_t n) const override { return t_.info[n].cost; }
  Bounds3 box(uint32_t n) const override { return t_.info[n].box; }
  std::string path(uint32_t n) const override { return kdNodePath(t_, n); }

 private:
  const KdTreeData& t_;
};

// The BVH: children are the next node and the stored second child; each node has its own tight box.
class BvhShape final : public TreeShape {
 public:
  explicit BvhShape(const BvhData& b) : b_(b) {}
  const char* name() const override { return "BVH"; }
  size_t size() const override { return b_.nodes.size(); }
  int32_t parent(uint32_t n) const override { return b_.info[n].parent; }
  int32_t depth(uint32_t n) const override { return b_.info[n].depth; }
  bool leaf(uint32_t n) const override { return b_.nodes[n].is_leaf(); }
  uint32_t child(uint32_t n, int row) const override { return row == 0 ? n + 1 : b_.nodes[n].second_child(); }
  QString what(uint32_t id) const override {
    const BvhNode& n = b_.nodes[id];
    if (n.is_leaf())
      return n.prim_count() == 0 ? QObject::tr("leaf, empty")
                                 : QObject::tr("leaf, %n primitive(s)", "", int(n.prim_count()));
    return QObject::tr("split on %1, %2 prims").arg(replay::axis_name(n.axis())).arg(b_.info[id].prims);
  }
  QString whatHeader() const override { return QObject::tr("split axis or leaf"); }
  float cost(uint32_t n) const override { return b_.info[n].cost; }
  Bounds3 box(uint32_t n) const override { return b_.nodes[n].box; }
  std::string path(uint32_t n) const override { return bvhNodePath(b_, n); }

 private:
  const BvhData& b_;
};

// The octree: eight children in one block, child i the octant (bit 0 upper in x, 1 y, 2 z); a 2D scene's
// quadtree four (the quadrant: bit 0 x, 1 y); no SAH.
class OctreeShape final : public TreeShape {
 public:
  explicit OctreeShape(const OctreeData& o) : o_(o) {}
  const char* name() const override { return "octree"; }
  size_t size() const override { return o_.nodes.size(); }
  int32_t parent(uint32_t n) const override { return o_.info[n].parent; }
  int32_t depth(uint32_t n) const override { return o_.info[n].depth; }
  bool leaf(uint32_t n) const override { return o_.nodes[n].is_leaf(); }
  uint32_t child(uint32_t n, int row) const override { return o_.nodes[n].child(row); }
  int children(uint32_t n) const override { return leaf(n) ? 0 : 1 << o_.axes; }
  int row(uint32_t n) const override {
    int32_t p = parent(n);
    return p < 0 ? 0 : int(n - o_.nodes[uint32_t(p)].first);
  }
  QString side(uint32_t n) const override {
    return parent(n) < 0 ? QObject::tr("root") : QString::fromStdString(replay::octant_name(row(n), o_.axes));
  }
  QString what(uint32_t id) const override {
    const OctreeNode& n = o_.nodes[id];
    if (n.is_leaf())
      return n.prim_count() == 0 ? QObject::tr("leaf, empty")
                                 : QObject::tr("leaf, %n primitive(s)", "", int(n.prim_count()));
    return (o_.axes == 2 ? QObject::tr("4 quadrants, %1 prims") : QObject::tr("8 octants, %1 prims"))
        .arg(o_.info[id].prims);
  }
  QString whatHeader() const override { return QObject::tr("cell"); }
  float cost(uint32_t n) const override { return float(o_.info[n].prims); }  // no SAH: the primitive count
  QString costHeader() const override { return QObject::tr("prims"); }
  Bounds3 box(uint32_t n) const override { return o_.info[n].box; }
  std::string path(uint32_t n) const override {
    std::string p;
    for (int32_t k = int32_t(n); parent(uint32_t(k)) >= 0; k = parent(uint32_t(k)))
      p.insert(0, std::to_string(row(uint32_t(k))));
    return p;
  }

 private:
  const OctreeData& o_;
};

// The general BSP tree: below L (the next node), above R, as the kd-tree; the box is the cell's bounding box.
class BspShape final : public TreeShape {
 public:
  explicit BspShape(const BspTreeData& b) : b_(b) {}
  const char* name() const override { return "BSP tree"; }
  size_t size() const override { return b_.nodes.size(); }
  int32_t parent(uint32_t n) const override { return b_.info[n].parent; }
  int32_t depth(uint32_t n) const override { return b_.info[n].depth; }
  bool leaf(uint32_t n) const override { return b_.nodes[n].is_leaf(); }
  uint32_t child(uint32_t n, int row) const override { return row == 0 ? n + 1 : b_.nodes[n].above_child(); }
  QString what(uint32_t id) const override {
    const BspNode& n = b_.nodes[id];
    if (n.is_leaf())
      return n.prim_count() == 0 ? QObject::tr("leaf, empty")
                                 : QObject::tr("leaf, %n primitive(s)", "", int(n.prim_count()));
    const glm::vec3 v = n.plane.normal;
    return QObject::tr("n = (%1, %2, %3), d = %4")
        .arg(double(v.x), 0, 'g', 3)
        .arg(double(v.y), 0, 'g', 3)
        .arg(double(v.z), 0, 'g', 3)
        .arg(double(n.plane.offset), 0, 'g', 5);
  }
  QString whatHeader() const override { return QObject::tr("plane or leaf"); }
  float cost(uint32_t n) const override { return b_.info[n].cost; }
  Bounds3 box(uint32_t n) const override { return b_.info[n].box; }
  std::string path(uint32_t n) const override {
    std::string p;
    for (int32_t k = int32_t(n); parent(uint32_t(k)) >= 0; k = parent(uint32_t(k)))
      p.insert(0, 1, row(uint32_t(k)) == 0 ? 'L' : 'R');
    return p;
  }

 private:
  const BspTreeData& b_;
};

// The wide BVH (bvh4, bvh8) as traces name its nodes (WideBvh::describe): up to 4 or 8 children each, with
// their own tight boxes (which may overlap); no SAH per node (collapsed from the binary tree), so the last
// column counts the primitives below.
class WideBvhShape final : public TreeShape {
 public:
  WideBvhShape(const WideBvhView& v, const std::vector<uint32_t>& prims, int width)
      : v_(v), prims_(prims), width_(width) {}
  const char* name() const override { return width_ == 4 ? "4-wide BVH" : "8-wide BVH"; }
  size_t size() const override { return v_.nodes.size(); }
  int32_t parent(uint32_t n) const override { return v_.nodes[n].parent; }
  int32_t depth(uint32_t n) const override { return v_.nodes[n].depth; }
  bool leaf(uint32_t n) const override { return v_.nodes[n].leaf; }
  uint32_t child(uint32_t n, int row) const override { return uint32_t(v_.nodes[n].children[size_t(row)]); }
  int children(uint32_t n) const override { return leaf(n) ? 0 : int(v_.nodes[n].children.size()); }
  int row(uint32_t n) const override {
    int32_t p = parent(n);
    if (p < 0) return 0;
    const std::vector<int32_t>& c = v_.nodes[size_t(p)].children;
    return int(std::find(c.begin(), c.end(), int32_t(n)) - c.begin());
  }
  QString side(uint32_t n) const override {
    int32_t p = parent(n);
    return p < 0 ? QObject::tr("root")
                 : QObject::tr("child %1/%2").arg(row(n) + 1).arg(v_.nodes[size_t(p)].children.size());
  }
  QString what(uint32_t id) const override {
    const WideBvhView::Node& n = v_.nodes[id];
    if (n.leaf)
      return n.prims.empty() ? QObject::tr("leaf, empty")
                             : QObject::tr("leaf, %n primitive(s)", "", int(n.prims.size()));
    return QObject::tr("%1 children, %2 prims").arg(n.children.size()).arg(prims_[id]);
  }
  QString whatHeader() const override { return QObject::tr("children or leaf"); }
  float cost(uint32_t n) const override { return float(prims_[n]); }
  QString costHeader() const override { return QObject::tr("prims"); }
  Bounds3 box(uint32_t n) const override { return v_.nodes[n].box; }
  std::string path(uint32_t n) const override {  // child numbers from the root, e.g. "3.1.7"
    std::string p;
    for (int32_t k = int32_t(n); parent(uint32_t(k)) >= 0; k = parent(uint32_t(k)))
      p.insert(0, std::to_string(row(uint32_t(k)) + 1) + (p.empty() ? "" : "."));
    return p;
  }

 private:
  const WideBvhView& v_;
  const std::vector<uint32_t>& prims_;
  int width_;
};

}  // namespace

std::unique_ptr<TreeShape> treeShapeOf(const StructureData& s) {
  if (const KdTree* kd = s.kdTree(); kd && !kd->data().nodes.empty())
    return std::make_unique<KdShape>(kd->data());
  if (const Bvh* bvh = s.bvh(); bvh && !bvh->data().nodes.empty())
    return std::make_unique<BvhShape>(bvh->data());
  if (const Octree* o = s.octree(); o && !o->data().nodes.empty())
    return std::make_unique<OctreeShape>(o->data());
  if (const BspTree* b = s.bsp(); b && !b->data().nodes.empty()) return std::make_unique<BspShape>(b->data());
  if (const WideBvh* w = s.wideBvh(); w && s.wideView && !s.wideView->nodes.empty())
    return std::make_unique<WideBvhShape>(*s.wideView, s.wideViewPrims, w->width());
  return nullptr;
}

void KdTreeModel::setStructure(std::shared_ptr<const StructureData> structure) {
  beginResetModel();
  structure_ = std::move(structure);
  tree_ = structure_ ? treeShapeOf(*structure_) : nullptr;
  endResetModel();
}

int KdTreeModel::rowOf(uint32_t node) const {
  return tree_->row(node);
}

QModelIndex KdTreeModel::indexOfNode(int node) const {
  if (!tree_ || node < 0 || size_t(node) >= tree_->size()) return {};
  return createIndex(rowOf(uint32_t(node)), 0, quintptr(node));
}

QModelIndex KdTreeModel::index(int row, int column, const QModelIndex& parent) const {
  if (!tree_ || column < 0 || column >= ColumnCount) return {};
  if (!parent.isValid()) return row == 0 ? createIndex(0, column, quintptr(0)) : QModelIndex();
  if (parent.column() != 0) return {};
  uint32_t p = uint32_t(parent.internalId());
  if (row < 0 || row >= tree_->children(p)) return {};
  return createIndex(row, column, quintptr(tree_->child(p, row)));
}

QModelIndex KdTreeModel::parent(const QModelIndex& child) const {
  if (!tree_ || !child.isValid()) return {};
  int32_t p = tree_->parent(uint32_t(child.internalId()));
  if (p < 0) return {};
  return createIndex(rowOf(uint32_t(p)), 0, quintptr(p));
}

int KdTreeModel::rowCount(const QModelIndex& parent) const {
  if (!tree_) return 0;
  if (!parent.isValid()) return 1;
  if (parent.column() != 0) return 0;
  return tree_->children(uint32_t(parent.internalId()));
}

int KdTreeModel::columnCount(const QModelIndex&) const {
  return ColumnCount;
}

bool KdTreeModel::hasChildren(const QModelIndex& parent) const {
  return rowCount(parent) > 0;
}

QVariant KdTreeModel::data(const QModelIndex& index, int role) const {
  if (!tree_ || !index.isValid()) return {};
  uint32_t id = uint32_t(index.internalId());
  if (role == Qt::DisplayRole) {
    switch (index.column()) {
      case SideColumn:
        return tree_->side(id);
      case NodeColumn:
        return id;
      case DepthColumn:
        return tree_->depth(id);
      case WhatColumn:
        return tree_->what(id);
      case CostColumn:
        return QString::number(double(tree_->cost(id)), 'g',
                               5);  // 3.6298e+06 fits the column; 3629800.0 did not
    }
  } else if (role == Qt::ToolTipRole) {
    const Bounds3 box = tree_->box(id);
    return tr("node %1, path \"%2\", box (%3, %4, %5) .. (%6, %7, %8)")
        .arg(id)
        .arg(QString::fromStdString(tree_->path(id)))
        .arg(double(box.lo.x), 0, 'g', 4)
        .arg(double(box.lo.y), 0, 'g', 4)
        .arg(double(box.lo.z), 0, 'g', 4)
        .arg(double(box.hi.x), 0, 'g', 4)
        .arg(double(box.hi.y), 0, 'g', 4)
        .arg(double(box.hi.z), 0, 'g', 4);
  }
  return {};
}

QVariant KdTreeModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (orientation != Qt::Horizontal || role != Qt::DisplayRole) return {};
  switch (section) {
    case SideColumn:
      return tr("tree");
    case NodeColumn:
      return tr("node");
    case DepthColumn:
      return tr("depth");
    case WhatColumn:
      return tree_ ? tree_->whatHeader() : tr("split or leaf");
    case CostColumn:
      return tree_ ? tree_->costHeader() : tr("cost");
  }
  return {};
}

}  // namespace raystep::viz
