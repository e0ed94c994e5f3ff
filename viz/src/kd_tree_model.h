// The kd-tree as a Qt item model for the tree view: a node's children are its below (L) and above (R) child,
// rows are made on demand from the node arrays (an index's internal id is the node id), so a tree of a
// million nodes costs nothing until a branch is expanded. Plus the two walks the views need: a node's path
// from the root ("LRL", the inverse of core's kd_node_by_path) and the leaf containing a point.
#pragma once

#include <memory>
#include <string>

#include <QAbstractItemModel>

#include "raystep/accel/kdtree_node.h"

namespace raystep::viz {

struct StructureData;

// 'L' for the child below the split plane (the node after its parent), 'R' for the one above; "" for the
// root.
std::string kdNodePath(const KdTreeData& tree, uint32_t node);
// The leaf whose box contains p (on a split plane: the child above); -1 when p is outside the root's box.
int kdLeafContaining(const KdTreeData& tree, const glm::vec3& p);

class KdTreeModel : public QAbstractItemModel {
  Q_OBJECT
 public:
  // The first column carries the tree's lines and the side (L, R); the id has its own so that deep rows show
  // it.
  enum Column { SideColumn, NodeColumn, DepthColumn, WhatColumn, CostColumn, ColumnCount };
  explicit KdTreeModel(QObject* parent = nullptr) : QAbstractItemModel(parent) {}

  // The structure whose kd-tree is shown (none, or a grid: an empty model); kept alive while shown.
  void setStructure(std::shared_ptr<const StructureData> structure);
  const KdTreeData* tree() const { return tree_; }
  QModelIndex indexOfNode(int node) const;  // invalid for no such node
  static int nodeOf(const QModelIndex& index) { return index.isValid() ? int(index.internalId()) : -1; }

  QModelIndex index(int row, int column, const QModelIndex& parent = QModelIndex()) const override;
  QModelIndex parent(const QModelIndex& child) const override;
  int rowCount(const QModelIndex& parent = QModelIndex()) const override;
  int columnCount(const QModelIndex& parent = QModelIndex()) const override;
  bool hasChildren(const QModelIndex& parent = QModelIndex()) const override;
  QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
  QVariant headerData(int section, Qt::Orientation orientation, int role = Qt::DisplayRole) const override;

 private:
  int rowOf(uint32_t node) const;  // 0: the root or a below child, 1: an above child
  std::shared_ptr<const StructureData> structure_;
  const KdTreeData* tree_ = nullptr;
};

}  // namespace raystep::viz
