#include "kd_tree_model.h"

#include <algorithm>

#include "replay.h"
#include "session.h"

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

void KdTreeModel::setStructure(std::shared_ptr<const StructureData> structure) {
  beginResetModel();
  structure_ = std::move(structure);
  const KdTree* kd = structure_ ? structure_->kdTree() : nullptr;
  tree_ = kd && !kd->data().nodes.empty() ? &kd->data() : nullptr;
  endResetModel();
}

int KdTreeModel::rowOf(uint32_t node) const {
  int32_t p = tree_->info[node].parent;
  return p < 0 || int32_t(node) == p + 1 ? 0 : 1;
}

QModelIndex KdTreeModel::indexOfNode(int node) const {
  if (!tree_ || node < 0 || size_t(node) >= tree_->nodes.size()) return {};
  return createIndex(rowOf(uint32_t(node)), 0, quintptr(node));
}

QModelIndex KdTreeModel::index(int row, int column, const QModelIndex& parent) const {
  if (!tree_ || column < 0 || column >= ColumnCount) return {};
  if (!parent.isValid()) return row == 0 ? createIndex(0, column, quintptr(0)) : QModelIndex();
  if (parent.column() != 0) return {};
  uint32_t p = uint32_t(parent.internalId());
  const KdNode& n = tree_->nodes[p];
  if (n.is_leaf() || row < 0 || row > 1) return {};
  return createIndex(row, column, quintptr(row == 0 ? p + 1 : n.above_child()));
}

QModelIndex KdTreeModel::parent(const QModelIndex& child) const {
  if (!tree_ || !child.isValid()) return {};
  int32_t p = tree_->info[size_t(child.internalId())].parent;
  if (p < 0) return {};
  return createIndex(rowOf(uint32_t(p)), 0, quintptr(p));
}

int KdTreeModel::rowCount(const QModelIndex& parent) const {
  if (!tree_) return 0;
  if (!parent.isValid()) return 1;
  if (parent.column() != 0) return 0;
  return tree_->nodes[size_t(parent.internalId())].is_leaf() ? 0 : 2;
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
  const KdNode& n = tree_->nodes[id];
  const KdNodeInfo& info = tree_->info[id];
  if (role == Qt::DisplayRole) {
    switch (index.column()) {
      case SideColumn:
        return info.parent < 0 ? tr("root") : index.row() == 0 ? QStringLiteral("L") : QStringLiteral("R");
      case NodeColumn:
        return id;
      case DepthColumn:
        return info.depth;
      case WhatColumn:
        if (n.is_leaf())
          return n.prim_count() == 0 ? tr("leaf, empty")
                                     : tr("leaf, %n primitive(s)", "", int(n.prim_count()));
        return tr("split %1 = %2").arg(axisName(n.axis())).arg(double(n.split), 0, 'g', 5);
      case CostColumn:
        return QString::number(double(info.cost), 'g', 5);  // 3.6298e+06 fits the column; 3629800.0 did not
    }
  } else if (role == Qt::ToolTipRole) {
    return tr("node %1, path \"%2\", box (%3, %4, %5) .. (%6, %7, %8)")
        .arg(id)
        .arg(QString::fromStdString(kdNodePath(*tree_, id)))
        .arg(double(info.box.lo.x), 0, 'g', 4)
        .arg(double(info.box.lo.y), 0, 'g', 4)
        .arg(double(info.box.lo.z), 0, 'g', 4)
        .arg(double(info.box.hi.x), 0, 'g', 4)
        .arg(double(info.box.hi.y), 0, 'g', 4)
        .arg(double(info.box.hi.z), 0, 'g', 4);
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
      return tr("split or leaf");
    case CostColumn:
      return tr("cost");
  }
  return {};
}

}  // namespace raystep::viz
