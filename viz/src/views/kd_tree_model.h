// The tree of a kd-tree or a binary BVH as a Qt item model for the tree view: a node's children are its two
// children (kd: below L and above R; BVH: left L and right R), rows are made on demand from the node arrays
// (an index's internal id is the node id), so a tree of a million nodes costs nothing until a branch is
// expanded. One small adapter per structure (TreeShape) says what a node is. Plus the two walks the views
// need: a node's path from the root ("LRL", the inverse of core's kd_node_by_path) and the leaf containing a
// point.
#pragma once

#include <memory>
#include <string>

#include <QAbstractItemModel>
#include <QObject>

#include <QString>

#include "raystep/accel/bvh_node.h"
#include "raystep/accel/kdtree_node.h"

namespace raystep::viz {

struct StructureData;

// 'L' for the child below the split plane (the node after its parent), 'R' for the one above; "" for the
// root.
std::string kdNodePath(const KdTreeData& tree, uint32_t node);
// The leaf whose box contains p (on a split plane: the child above); -1 when p is outside the root's box.
int kdLeafContaining(const KdTreeData& tree, const glm::vec3& p);

// 'L' for a BVH node's first child (the node after its parent), 'R' for the second; "" for the root.
std::string bvhNodePath(const BvhData& bvh, uint32_t node);

// What the tree view and the tree model need of a binary tree, one adapter per structure.
class TreeShape {
 public:
  virtual ~TreeShape() = default;
  virtual const char* name() const = 0;  // "kd-tree", "BVH"
  virtual size_t size() const = 0;
  virtual int32_t parent(uint32_t node) const = 0;  // -1: the root
  virtual int32_t depth(uint32_t node) const = 0;
  virtual bool leaf(uint32_t node) const = 0;
  virtual uint32_t child(uint32_t node, int row) const = 0;  // row 0 .. children - 1 of an inner node
  // Binary trees: 2 children, rows L and R; the octree: 8, rows named by their octant.
  virtual int children(uint32_t node) const { return leaf(node) ? 0 : 2; }
  virtual int row(uint32_t node) const {  // its row under its parent (0: the root, or the next node)
    int32_t p = parent(node);
    return p < 0 || int32_t(node) == p + 1 ? 0 : 1;
  }
  virtual QString side(uint32_t node) const {  // the tree column: "root", "L", "R", "x+ y- z+"
    return parent(node) < 0 ? QObject::tr("root")
           : row(node) == 0 ? QStringLiteral("L")
                            : QStringLiteral("R");
  }
  virtual QString what(uint32_t node) const = 0;             // "split x = 0.5", "leaf, 3 primitives"
  virtual QString whatHeader() const = 0;
  virtual float cost(uint32_t node) const = 0;
  virtual QString costHeader() const { return QObject::tr("cost"); }  // the octree, a wide BVH: "prims"
  virtual Bounds3 box(uint32_t node) const = 0;
  virtual std::string path(uint32_t node) const = 0;
};
// The adapter for a structure's tree: a kd-tree, a binary BVH, a wide BVH (up to 4 or 8 children a node), an
// octree, a general BSP tree, or null (a grid).
std::unique_ptr<TreeShape> treeShapeOf(const StructureData& s);

class KdTreeModel : public QAbstractItemModel {
  Q_OBJECT
 public:
  // The first column carries the tree's lines and the side (L, R); the id has its own so that deep rows show
  // it.
  enum Column { SideColumn, NodeColumn, DepthColumn, WhatColumn, CostColumn, ColumnCount };
  explicit KdTreeModel(QObject* parent = nullptr) : QAbstractItemModel(parent) {}

  // The structure whose tree is shown (none, or a grid: an empty model); kept alive while shown.
  void setStructure(std::shared_ptr<const StructureData> structure);
  const TreeShape* tree() const { return tree_.get(); }
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
  std::unique_ptr<TreeShape> tree_;
};

}  // namespace raystep::viz
