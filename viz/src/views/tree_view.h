// The kd-tree's nodes as a tree (id, depth, split plane or leaf, cost), rows made only as branches open. The
// selection is the session's selected node both ways: picking a row asks for it (nodeChosen), and a node
// chosen elsewhere (the 3D view, the scripted mode) is expanded to and shown. "Current node" goes to the node
// the replayed ray is in.
#pragma once

#include <QWidget>

class QLabel;
class QPushButton;
class QTreeView;

namespace raystep::viz {

class KdTreeModel;
class Session;

class TreeView : public QWidget {
  Q_OBJECT
 public:
  explicit TreeView(Session* session, QWidget* parent = nullptr);
  QTreeView* view() const { return view_; }
  int expandedCount() const;
  // Back to the rows a new tree shows (the root's children, then the way to the selected node): entering a
  // lesson step leaves no rows open from the steps before.
  void resetRows();  // rows the view has made, for the dump (never the whole tree)

 Q_SIGNALS:
  void nodeChosen(int node);

 private:
  void showSelected();
  QString qualityText() const;
  Session* session_;
  KdTreeModel* model_;
  QTreeView* view_;
  QLabel* title_;
  QPushButton* current_;
  bool syncing_ = false;
};

}  // namespace raystep::viz
