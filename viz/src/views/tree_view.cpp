#include "views/tree_view.h"

#include <functional>

#include <QHBoxLayout>
#include <QHeaderView>
#include <QItemSelectionModel>
#include <QLabel>
#include <QPushButton>
#include <QTreeView>
#include <QVBoxLayout>

#include "views/kd_tree_model.h"
#include "app/session.h"

namespace raystep::viz {

TreeView::TreeView(Session* session, QWidget* parent)
    : QWidget(parent), session_(session), model_(new KdTreeModel(this)) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  auto* bar = new QHBoxLayout;
  title_ = new QLabel(tr("<b>kd-tree</b>"));
  title_->setWordWrap(true);  // a BVH's title carries its quality metrics
  current_ = new QPushButton(tr("Current node"));
  current_->setObjectName("treeCurrentNode");
  current_->setToolTip(tr("Expand the tree to the node the replayed ray is in"));
  bar->addWidget(title_, 1);
  bar->addWidget(current_);
  layout->addLayout(bar);
  view_ = new QTreeView;
  view_->setObjectName("kdTreeView");
  view_->setModel(model_);
  view_->setUniformRowHeights(true);  // no per-row size queries: fast on deep trees
  view_->setSelectionMode(QAbstractItemView::SingleSelection);
  view_->setIndentation(10);
  view_->setAllColumnsShowFocus(true);
  view_->header()->setStretchLastSection(true);  // the cost column takes the room that is left
  view_->header()->setSectionResizeMode(KdTreeModel::SideColumn, QHeaderView::ResizeToContents);
  view_->setColumnWidth(KdTreeModel::NodeColumn, 60);
  view_->setColumnWidth(KdTreeModel::DepthColumn, 40);
  view_->setColumnWidth(KdTreeModel::WhatColumn, 150);
  view_->setColumnWidth(KdTreeModel::CostColumn, 70);
  layout->addWidget(view_, 1);

  connect(view_->selectionModel(), &QItemSelectionModel::currentChanged, this, [this](const QModelIndex& i) {
    if (!syncing_ && i.isValid()) Q_EMIT nodeChosen(KdTreeModel::nodeOf(i));
  });
  connect(current_, &QPushButton::clicked, this, [this] {
    const TracedRay* ray = session_->ray();
    int e = session_->state().node_event;
    if (ray && e >= 0 && e < int(ray->events.size())) Q_EMIT nodeChosen(ray->events[size_t(e)].node);
  });
  connect(session_, &Session::structureChanged, this, [this] {
    model_->setStructure(session_->structureShared());
    if (const TreeShape* t = model_->tree())
      title_->setText(tr("<b>%1</b>: %2 nodes").arg(t->name()).arg(t->size()) + qualityText());
    else
      title_->setText(tr("<b>Tree</b>: none (build a kd-tree or a BVH)"));
    view_->expandToDepth(0);  // the root's two children
    showSelected();
  });
  connect(session_, &Session::selectedNodeChanged, this, &TreeView::showSelected);
  connect(session_, &Session::stepChanged, this,
          [this] { current_->setEnabled(session_->state().node_event >= 0); });
  current_->setEnabled(false);
}

// A BVH's quality (core's bvh_quality.h, measured with the build): SAH, EPO and the leaves' sizes.
QString TreeView::qualityText() const {
  const StructureData* s = session_->structure();
  if (!s || !s->quality) return QString();
  const BvhQuality& q = *s->quality;
  QString sizes;
  int shown = 0;
  for (size_t k = 0; k < q.leaf_prims.size() && shown < 4; ++k)
    if (q.leaf_prims[k] > 0) {
      sizes += tr("%1%2 of %3%4")
                   .arg(shown ? ", " : "")
                   .arg(q.leaf_prims[k])
                   .arg(k)
                   .arg(k + 1 == q.leaf_prims.size() ? "+" : "");
      ++shown;
    }
  size_t depth = 0;
  uint64_t most = 0;
  for (size_t d = 0; d < q.leaf_depth.size(); ++d)
    if (q.leaf_depth[d] > most) most = q.leaf_depth[d], depth = d;
  const QString epo = q.epo_measured
                          ? QString::number(q.epo, 'f', 2)
                          : tr("not measured beyond %L1 primitives (raystep bvh-stats)").arg(qulonglong(kEpoTriangles));
  return tr(" &middot; SAH %1 &middot; EPO %2 &middot; leaves: %3 primitives &middot; most at depth %4")
      .arg(q.sah_cost, 0, 'f', 1)
      .arg(epo)
      .arg(sizes)
      .arg(depth);
}

void TreeView::showSelected() {
  syncing_ = true;
  QModelIndex i = model_->indexOfNode(session_->selectedNode());
  if (i.isValid()) {
    for (QModelIndex p = i.parent(); p.isValid(); p = p.parent()) view_->expand(p);
    view_->selectionModel()->setCurrentIndex(i,
                                             QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
    view_->scrollTo(i.siblingAtColumn(KdTreeModel::NodeColumn));
  } else {
    view_->selectionModel()->clearSelection();
  }
  syncing_ = false;
}

void TreeView::resetRows() {
  syncing_ = true;
  view_->collapseAll();
  view_->selectionModel()->clear();
  view_->expandToDepth(0);
  syncing_ = false;
  showSelected();
}

int TreeView::expandedCount() const {
  // Rows made so far: walk only the expanded branches.
  int n = 0;
  std::function<void(const QModelIndex&)> walk = [&](const QModelIndex& parent) {
    int rows = model_->rowCount(parent);
    for (int r = 0; r < rows; ++r) {
      ++n;
      QModelIndex c = model_->index(r, 0, parent);
      if (view_->isExpanded(c)) walk(c);
    }
  };
  walk(QModelIndex());
  return n;
}

}  // namespace raystep::viz
