#include "views/state_panel.h"

#include <algorithm>
#include <cmath>

#include <QAbstractTableModel>
#include <QFormLayout>
#include <QGroupBox>
#include <QHeaderView>
#include <QJsonArray>
#include <QLabel>
#include <QRegularExpression>
#include <QTableView>
#include <QTableWidget>
#include <QVBoxLayout>

#include "raystep/trace/node_path.h"
#include "raystep/replay/replay_state.h"
#include "raystep/replay/node_crossing.h"
#include "raystep/replay/octree_choice.h"
#include "raystep/replay/bvh_choice.h"
#include "raystep/replay/explain.h"
#include "app/session.h"

namespace raystep::viz {
namespace {

QString num(float v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return QString::number(double(v), 'g', 5);
}

}  // namespace

// The primitives tested so far for this ray: the mailbox's contents.
class MailboxModel : public QAbstractTableModel {
 public:
  using QAbstractTableModel::QAbstractTableModel;
  // A step adds or removes a few rows at the end: tell the view just that (a reset of 30,000 rows is slow).
  void setEntries(const std::vector<replay::MailboxEntry>* entries) {
    int before = shown_, after = entries ? int(entries->size()) : 0;
    if (after > before) {
      beginInsertRows({}, before, after - 1);
      entries_ = entries;
      shown_ = after;
      endInsertRows();
    } else if (after < before) {
      beginRemoveRows({}, after, before - 1);
      entries_ = entries;
      shown_ = after;
      endRemoveRows();
    } else {
      entries_ = entries;
    }
    if (after > 0) Q_EMIT dataChanged(index(0, 0), index(after - 1, 3));
  }
  int rowCount(const QModelIndex& = {}) const override { return shown_; }
  int columnCount(const QModelIndex& = {}) const override { return 4; }
  QVariant headerData(int section, Qt::Orientation o, int role) const override {
    if (role != Qt::DisplayRole || o != Qt::Horizontal) return {};
    static const char* names[] = {"prim", "tested in", "result", "skips"};
    return names[section];
  }
  QVariant data(const QModelIndex& index, int role) const override {
    if (!entries_ || role != Qt::DisplayRole) return {};
    return cell(index.row(), index.column());
  }
  QString cell(int row, int col) const {
    const replay::MailboxEntry& m = (*entries_)[size_t(row)];
    switch (col) {
      case 0: return QString::number(m.prim);
      case 1:
        if (m.tested_in_cell_event >= 0) return QString("(%1,%2,%3)").arg(m.cell[0]).arg(m.cell[1]).arg(m.cell[2]);
        return m.leaf >= 0 ? QString("leaf %1").arg(m.leaf) : QString("-");
      case 2: return m.hit ? QString("hit t=%1").arg(num(m.t)) : QString("miss");
      default: return QString::number(m.skips);
    }
  }

 private:
  const std::vector<replay::MailboxEntry>* entries_ = nullptr;
  int shown_ = 0;
};

StatePanel::StatePanel(Session* session, QWidget* parent) : QWidget(parent), session_(session) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  auto label = [](const QString& name) {
    auto* l = new QLabel;
    l->setObjectName(name);
    l->setTextFormat(Qt::RichText);
    l->setWordWrap(true);
    l->setTextInteractionFlags(Qt::TextSelectableByMouse);
    return l;
  };
  ray_ = label("rayLabel");
  event_ = label("eventLabel");
  layout->addWidget(ray_);
  layout->addWidget(event_);

  auto* ruleBox = new QGroupBox(tr("Why"));
  auto* ruleLayout = new QVBoxLayout(ruleBox);
  rule_ = label("ruleLabel");
  rule_->setTextFormat(Qt::PlainText);
  ruleLayout->addWidget(rule_);
  layout->addWidget(ruleBox);

  gridBox_ = new QGroupBox(tr("Grid: 3D-DDA"));
  auto* form = new QFormLayout(gridBox_);
  cell_ = label("cellLabel");
  interval_ = label("intervalLabel");
  dda_ = label("ddaLabel");
  nearest_ = label("nearestLabel");
  form->addRow(tr("cell (i,j,k)"), cell_);
  form->addRow(tr("[t_enter, t_exit]"), interval_);
  form->addRow(dda_);
  layout->addWidget(gridBox_);

  // Trees (kd-tree): the current node and the stack, shown when the trace has tree events.
  treeBox_ = new QGroupBox(tr("Tree: stack traversal"));
  auto* treeForm = new QFormLayout(treeBox_);
  node_ = label("nodeLabel");
  crossing_ = label("crossingLabel");
  stack_ = new QTableWidget(0, 4);
  stack_->setObjectName("stackTable");
  stack_->setHorizontalHeaderLabels({tr("node"), tr("depth"), tr("t_min"), tr("t_max")});
  stack_->verticalHeader()->hide();
  stack_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  stack_->verticalHeader()->setDefaultSectionSize(18);
  stack_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  stack_->setSelectionMode(QAbstractItemView::NoSelection);
  stack_->setFocusPolicy(Qt::NoFocus);
  stack_->setVerticalScrollBarPolicy(Qt::ScrollBarAsNeeded);
  // Room for five entries: a bunny's walk keeps up to six on the stack, and two rows told too little.
  stack_->setMinimumHeight(stack_->horizontalHeader()->sizeHint().height() + 5 * 18 + 4);
  treeForm->addRow(tr("node"), node_);
  crossingTitle_ = new QLabel(tr("t*"));
  treeForm->addRow(crossingTitle_, crossing_);
  stackTitle_ = new QLabel(tr("stack (top first; pushed far children)"));
  stackTitle_->setWordWrap(true);
  treeForm->addRow(stackTitle_);
  treeForm->addRow(stack_);
  treeBox_->hide();
  layout->addWidget(treeBox_);

  // The nearest hit so far, for grids and trees alike: the stop rules compare with its t.
  auto* hitForm = new QFormLayout;
  hitForm->addRow(tr("<b>nearest hit</b>"), nearest_);
  layout->addLayout(hitForm);

  auto* counterBox = new QGroupBox(tr("Counters so far"));
  auto* counterLayout = new QVBoxLayout(counterBox);
  counters_ = label("countersLabel");
  counterLayout->addWidget(counters_);
  layout->addWidget(counterBox);

  auto* mailBox = mailBoxGroup_ = new QGroupBox(tr("Mailbox: this ray's tests"));
  mailboxBox_ = mailBox;
  auto* mailLayout = new QVBoxLayout(mailBox);
  mailLayout->setContentsMargins(2, 2, 2, 2);
  mailbox_ = new MailboxModel(this);
  mailboxView_ = new QTableView;
  mailboxView_->setObjectName("mailboxTable");
  mailboxView_->setModel(mailbox_);
  mailboxView_->verticalHeader()->hide();
  mailboxView_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  mailboxView_->verticalHeader()->setDefaultSectionSize(18);
  mailboxView_->setFocusPolicy(Qt::NoFocus);
  mailLayout->addWidget(mailboxView_);
  layout->addStretch();

  connect(session_, &Session::stepChanged, this, &StatePanel::refresh);
  connect(session_, &Session::traceChanged, this, &StatePanel::refresh);
  connect(session_, &Session::structureChanged, this, &StatePanel::refresh);
  refresh();
}

namespace {

// An anti-aliased pixel's ray names the sample it descends from and where that sample lies in the pixel.
QString sampleText(const TracePixel* px, const TracedRay& r) {
  if (!px || r.sample < 0 || r.sample >= int(px->sampling.samples.size())) return QString();
  const PixelSample& ps = px->sampling.samples[size_t(r.sample)];
  return QObject::tr(", sample %1 at (%2, %3) in the pixel")
      .arg(r.sample)
      .arg(double(ps.px) - px->sampling.x, 0, 'f', 3)
      .arg(double(ps.py) - px->sampling.y, 0, 'f', 3);
}

}  // namespace

void StatePanel::refresh() {
  const TracedRay* r = session_->ray();
  const replay::ReplayState& s = session_->state();
  mailbox_->setEntries(r ? &s.mailbox : nullptr);
  if (!r || !s.event) {
    ray_->setText(tr("<i>No ray yet. Click a pixel in the image, or open a trace.</i>"));
    for (QLabel* l : {event_, cell_, interval_, dda_, nearest_, rule_, counters_, node_, crossing_}) l->clear();
    stack_->setRowCount(0);
    // Before a ray, the boxes of the structure that is built.
    const bool tree = session_->structure() && session_->structure()->kind != "grid";
    const bool bvh = session_->structure() && replay::is_bvh_kind(session_->structure()->kind);
    treeBox_->setTitle(bvh ? tr("BVH: stack traversal") : tr("Tree: stack traversal"));
    crossingTitle_->setText(bvh ? tr("children") : tr("t*"));
    mailBoxGroup_->setTitle(bvh ? tr("Tests (each in one leaf)")
                                : tr("Mailbox: this ray's tests"));
    treeBox_->setVisible(tree);
    gridBox_->setVisible(!tree);
    return;
  }
  const bool tree = replay::is_tree_ray(*r);
  const bool bvh = replay::is_bvh_ray(session_->trace(), *r);
  treeBox_->setVisible(tree || bvh);
  treeBox_->setTitle(bvh ? tr("BVH: stack traversal") : tr("Tree: stack traversal"));
  const bool octree = replay::is_octree_ray(session_->trace(), *r);
  treeBox_->setTitle(bvh      ? tr("BVH: stack traversal")
                     : octree ? tr("Octree: Revelles' traversal")
                              : tr("Tree: stack traversal"));
  crossingTitle_->setText(bvh || octree ? tr("children") : tr("t*"));
  // The octree's stack holds the cells whose children are being walked, not far children.
  stackTitle_->setText(octree ? tr("stack (top first; cells being walked)")
                              : tr("stack (top first; pushed far children)"));
  mailBoxGroup_->setTitle(bvh ? tr("Tests (each in one leaf)")
                              : tr("Mailbox: this ray's tests"));
  gridBox_->setVisible(!tree || s.cell_event >= 0);
  if (tree || bvh) refreshTree(*r, s);
  ray_->setText(
      tr("<b>Ray</b> %1, depth %2%3: o = (%4, %5, %6), d = (%7, %8, %9)")
          .arg(ray_kind_name(r->kind))
          .arg(r->depth)
          .arg((r->has_pixel ? tr(", pixel (%1, %2)").arg(r->pixel[0]).arg(r->pixel[1]) : QString()) +
               sampleText(session_->pixel(), *r))
          .arg(num(r->ray.origin.x), num(r->ray.origin.y), num(r->ray.origin.z))
          .arg(num(r->ray.direction.x), num(r->ray.direction.y), num(r->ray.direction.z)));
  QString line = QString::fromStdString(replay::describe_event(*s.event));
  if (conceal_) line.remove(QRegularExpression("\\s+next \\w+$"));  // a cell's line names the next axis
  event_->setText(tr("<b>Event</b> %1").arg(line.toHtmlEscaped()));

  if (s.cell_event >= 0) {
    const Event& c = r->events[size_t(s.cell_event)];
    cell_->setText(QString("<b>(%1, %2, %3)</b>").arg(c.cell[0]).arg(c.cell[1]).arg(c.cell[2]));
    interval_->setText(QString("[%1, %2]").arg(num(c.t_enter), num(c.t_exit)));
    QString t = "<table cellspacing=4><tr><th></th><th>x</th><th>y</th><th>z</th></tr><tr><td>tMax</td>";
    for (int a = 0; a < 3; ++a)
      t += a == c.next_axis && !conceal_ ? QString("<td><b><u>%1</u></b></td>").arg(num(c.t_max[a]))
                            : QString("<td>%1</td>").arg(num(c.t_max[a]));
    t += "</tr><tr><td>tDelta</td>";
    for (int a = 0; a < 3; ++a) t += QString("<td>%1</td>").arg(num(c.t_delta[a]));
    if (conceal_)
      t += tr("</tr></table>next axis: <i>? (the quiz asks it)</i>");
    else
      t += QString("</tr></table>next axis: <b>%1</b>%2")
               .arg(replay::axis_name(c.next_axis))
               .arg(c.next_axis >= 0 ? tr(" (smallest tMax)") : tr(" (the walk ends in this cell)"));
    dda_->setText(t);
  } else {
    cell_->setText(tr("<i>not in the grid yet</i>"));
    interval_->clear();
    dda_->clear();
  }
  if (s.nearest_prim >= 0)
    nearest_->setText(tr("prim %1 at t = %2 <b>%3</b>")
                          .arg(s.nearest_prim)
                          .arg(num(s.nearest_t))
                          .arg(s.accepted ? tr("(accepted)") : s.deferred ? tr("(deferred: beyond the cell's exit)")
                                                                          : tr("(candidate)")));
  else nearest_->setText(s.ended ? tr("none: a miss") : tr("none yet"));
  rule_->setText(conceal_ ? tr("Shown with the answer.")
                          : QString::fromStdString(replay::explain_rule(session_->trace(), *r, s)));
  const RayCounters& k = s.counters;
  QString walk = bvh ? tr("nodes %1 &nbsp; box tests %2 &nbsp; pushes %3 &nbsp; pops %4 &nbsp; skips %5")
                           .arg(k.nodes)
                           .arg(k.box_tests)
                           .arg(k.pushes)
                           .arg(k.pops)
                           .arg(s.skipped_nodes.size())
                 : tree
                     ? tr("nodes %1 &nbsp; pushes %2 &nbsp; pops %3").arg(k.nodes).arg(k.pushes).arg(k.pops)
                     : tr("cells %1").arg(k.cells);
  counters_->setText(walk + tr("<br>primitive tests %1 &nbsp; hits %2 &nbsp; mailbox hits %3")
                                .arg(k.prim_tests)
                                .arg(k.prim_hits)
                                .arg(k.mailbox_hits));
  if (s.event->type == EventType::prim_test) mailboxView_->scrollToBottom();
}

void StatePanel::refreshTree(const TracedRay& r, const replay::ReplayState& s) {
  if (s.node_event >= 0) {
    const Event& n = r.events[size_t(s.node_event)];
    const TraceNode* tn = session_->trace() ? replay::find_node(*session_->trace(), n.node) : nullptr;
    const bool bvh = replay::is_bvh_ray(session_->trace(), r);
    const bool octree = replay::is_octree_ray(session_->trace(), r);
    QString what = !tn        ? QString(event_type_name(n.type))
                   : tn->leaf ? tr("leaf, %1 primitives").arg(tn->prims.size())
                   : bvh      ? (tn->axis >= 0 ? tr("inner, %1 children, built split on %2")
                                                .arg(tn->children.size())
                                                .arg(replay::axis_name(tn->axis))
                                               : tr("inner, %1 children (a wide node)").arg(tn->children.size()))
                   : tn->has_plane
                       ? tr("inner, plane n = (%1, %2, %3), d = %4")
                             .arg(num(tn->normal.x), num(tn->normal.y), num(tn->normal.z), num(tn->offset))
                   : octree ? (tn->children.size() == 4 ? tr("inner cell, 4 children: a quadtree's quadrants")
                                                        : tr("inner cell, 8 children"))
                            : tr("inner, split %1 = %2").arg(replay::axis_name(tn->axis)).arg(num(tn->split));
    const std::string path = session_->trace() ? trace_node_path_text(*session_->trace(), n.node) : "";
    node_->setText(tr("<b>%1</b> (%2), depth %3%7, [t_min, t_max] = [%4, %5]%6")
                       .arg(n.node)
                       .arg(what)
                       .arg(n.depth)
                       .arg(num(n.t_min_node), num(n.t_max_node))
                       .arg(n.type == EventType::pop ? tr(" <i>popped</i>") : QString())
                       .arg(path.empty() ? QString() : QString(", path <b>%1</b>").arg(QString::fromStdString(path))));
  } else {
    node_->setText(tr("<i>not in the tree yet</i>"));
  }
  if (replay::is_bvh_ray(session_->trace(), r)) {
    refreshBvhChildren(r, s);
  } else if (replay::is_octree_ray(session_->trace(), r)) {
    refreshOctreeChildren(r, s);
  } else if (replay::NodeCrossing c = session_->trace() ? replay::node_crossing(*session_->trace(), r, s) : replay::NodeCrossing{};
             c.valid) {
    auto child = [](int32_t id) { return id >= 0 ? QString::number(id) : QString("-"); };
    QString which;
    switch (c.crossing) {
      case replay::Crossing::near_only:
        which = (std::isinf(c.t_star) ? tr("parallel to the plane") : tr("t* &gt; t_max")) +
                tr(": <b>near child only</b> (%1)").arg(child(c.near_child));
        break;
      case replay::Crossing::far_only:
        which = (std::isinf(c.t_star) ? tr("parallel to the plane") : tr("t* &lt; t_min")) +
                tr(": <b>far child only</b> (%1)").arg(child(c.far_child));
        break;
      case replay::Crossing::both:
        which = (c.t_star >= c.t_min && c.t_star <= c.t_max ? tr("t_min &le; t* &le; t_max")
                                                         : tr("t* at the interval's edge (within the margin)")) +
                tr(": <b>both</b>: near %1 [t_min, t*], far %2 [t*, t_max] pushed").arg(child(c.near_child), child(c.far_child));
        break;
      case replay::Crossing::in_plane:
        which = tr("the ray lies in the plane: <b>both</b>, near %1, far %2 over the whole interval")
                    .arg(child(c.near_child), child(c.far_child));
        break;
    }
    if (c.general) {  // a BSP plane: n, d, the origin's side and t* = (d - n.o) / (n.dir)
      const QString plane =
          tr("n.o - d = %1, n.dir = %2").arg(num(float(c.origin_side)), num(float(c.n_dot_dir)));
      if (conceal_)
        crossing_->setText(tr("<b>%1</b> (%2)<br><i>near side and children: ? (the quiz asks it)</i>")
                               .arg(num(c.t_star), plane));
      else
        crossing_->setText(tr("<b>%1</b> = (d - n.o) / (n.dir) (%2; near side %3)<br>%4")
                               .arg(num(c.t_star), plane)
                               .arg(c.near_is_below ? tr("below") : tr("above"))
                               .arg(which));
    } else if (conceal_)  // the quiz asks which child comes first: t* and the plane only
      crossing_->setText(tr("<b>%1</b> (plane %2 = %3)<br><i>near side and children: ? (the quiz asks it)</i>")
                             .arg(num(c.t_star))
                             .arg(replay::axis_name(c.axis))
                             .arg(num(c.split)));
    else
      crossing_->setText(tr("<b>%1</b> (plane %2 = %3; near side %4)<br>%5")
                             .arg(num(c.t_star))
                             .arg(replay::axis_name(c.axis))
                             .arg(num(c.split))
                             .arg(c.near_is_below ? tr("below") : tr("above"))
                             .arg(which));
  } else {
    crossing_->setText(tr("<i>none: no split at this event</i>"));
  }
  // The stack, top first; the entry just pushed in bold.
  int rows = int(s.stack.size());
  stack_->setRowCount(rows);
  // As tall as its rows (at least one, at most eight), so that the panel below it stays in view.
  stack_->setFixedHeight(stack_->horizontalHeader()->height() + rowHeight_ * std::clamp(rows, 1, 8) + 4);
  for (int row = 0; row < rows; ++row) {
    const replay::StackEntry& e = s.stack[size_t(rows - 1 - row)];
    // The node by id and by its path in the slides' notation (LLR: below, below, above).
    const std::string path = session_->trace() ? trace_node_path_text(*session_->trace(), e.node) : "";
    QString cells[4] = {path.empty() ? QString::number(e.node)
                                     : QString("%1 (%2)").arg(e.node).arg(QString::fromStdString(path)),
                        QString::number(e.depth), num(e.t_min), num(e.t_max)};
    bool justPushed = e.push_event == s.step;
    for (int col = 0; col < 4; ++col) {
      auto* item = stack_->item(row, col);
      if (!item) {
        item = new QTableWidgetItem;
        stack_->setItem(row, col, item);
      }
      item->setText(cells[col]);
      QFont f = item->font();
      f.setBold(justPushed);
      item->setFont(f);
    }
  }
}

void StatePanel::refreshBvhChildren(const TracedRay& r, const replay::ReplayState& s) {
  // Each child's box test as far as the walk is (a test not reached yet: "?"), then the order chosen.
  replay::BvhChoice c = replay::bvh_choice(r, s);
  if (!c.valid) {
    crossing_->setText(tr("<i>- (the current node is not an inner node whose children are tested)</i>"));
    return;
  }
  QString t;
  for (const replay::BoxTestMark& m : c.tests) {
    QString result = !m.done ? tr("<i>?</i>")
                     : m.hit ? QString("[%1, %2]").arg(num(m.t_near), num(m.t_far))
                             : tr("<b>miss</b>");
    t += tr("child %1: %2<br>").arg(m.child).arg(result);
  }
  if (!c.decided || conceal_) {
    t += tr("<i>order: ? (after the box tests%1)</i>").arg(conceal_ ? tr("; the quiz asks it") : QString());
  } else if (c.first < 0) {
    t += tr("<b>no child hit</b>: go on with the stack");
  } else {
    QStringList pushed;
    for (int32_t p : c.pushed) pushed << QString::number(p);
    t += tr("<b>nearer first</b>: enter %1%2")
             .arg(c.first)
             .arg(pushed.isEmpty() ? QString() : tr("; pushed %1").arg(pushed.join(", ")));
  }
  crossing_->setText(t);
}

void StatePanel::refreshOctreeChildren(const TracedRay& r, const replay::ReplayState& s) {
  // The children in the order the ray crosses them (Revelles: the entry plane picks the first, each exit
  // plane the next), those visited so far in bold.
  replay::OctreeChoice c = session_->trace() ? replay::octree_choice(*session_->trace(), r, s) : replay::OctreeChoice{};
  if (!c.valid) {
    // A leaf: its exit t per axis; the smallest is the exit plane, across which the next cell lies.
    const TraceNode* n = session_->trace() && s.node_event >= 0
                             ? replay::find_node(*session_->trace(), r.events[size_t(s.node_event)].node)
                             : nullptr;
    if (n && n->leaf) {
      QStringList exits;
      int exit = -1;
      float best = 0.f;
      for (int a = 0; a < 3; ++a) {
        const float d = r.ray.direction[a], inv = 1.f / d;
        if (!std::isfinite(inv)) continue;
        const float t1 = ((std::signbit(d) ? n->box.lo[a] : n->box.hi[a]) - r.ray.origin[a]) * inv;
        exits << tr("%1 at %2").arg(replay::axis_name(a)).arg(num(t1));
        if (exit < 0 || t1 < best) exit = a, best = t1;
      }
      crossing_->setText(
          tr("leaf cell; exit planes: %1").arg(exits.join(", ")) +
          (conceal_ || exit < 0 ? QString() : tr("<br>leaves by %1 (the smallest)").arg(replay::axis_name(exit))));
      return;
    }
    crossing_->setText(tr("<i>- (the current node is not an inner cell whose children are walked)</i>"));
    return;
  }
  QString t = c.entry_axis >= 0
                  ? tr("entry plane %1 at t = %2").arg(replay::axis_name(c.entry_axis)).arg(num(c.t0[c.entry_axis]))
                  : QString();
  // The centre planes' t: with the entry t, Revelles' first child (the far half where one comes before it).
  QStringList mids;
  for (int a = 0; a < c.axes; ++a)  // a quadtree has none on z
    if (c.moving[a]) mids << tr("%1 at %2").arg(replay::axis_name(a)).arg(num(c.t_mid[a]));
  if (!mids.isEmpty())
    t += (t.isEmpty() ? QString() : QString("<br>")) + tr("centre planes: ") + mids.join(", ");
  if (conceal_) {
    crossing_->setText(t + tr("<br><i>order: ? (the quiz asks it)</i>"));
    return;
  }
  // One line per child, numbered in the order the ray crosses them, with the plane it is left by.
  for (size_t k = 0; k < c.path.size(); ++k) {
    const replay::OctreeChildStep& st = c.path[k];
    const bool seen = std::find(c.visited.begin(), c.visited.begin() + c.visited_so_far, st.node) !=
                      c.visited.begin() + c.visited_so_far;
    QString item =
        QString("%1. %2 [%3]").arg(k + 1).arg(st.node).arg(QString::fromStdString(replay::octant_name(st.octant, c.axes)));
    t += "<br>" + (seen ? "<b>" + item + "</b>" : item) +
         (st.leaves_parent
              ? tr(", leaves the cell by %1 at t = %2").arg(replay::axis_name(st.exit_axis)).arg(num(st.t_exit))
              : tr(", exit plane %1 at t = %2").arg(replay::axis_name(st.exit_axis)).arg(num(st.t_exit)));
  }
  crossing_->setText(t);
}

void StatePanel::setConceal(bool on) {
  if (on == conceal_) return;
  conceal_ = on;
  refresh();
}

void StatePanel::setScale(double scale) {
  rowHeight_ = int(std::lround(18 * scale));
  stack_->verticalHeader()->setDefaultSectionSize(rowHeight_);
  stack_->setMinimumHeight(stack_->horizontalHeader()->sizeHint().height() + 5 * rowHeight_ + 4);
  mailboxView_->verticalHeader()->setDefaultSectionSize(rowHeight_);
  refresh();
}

QJsonObject StatePanel::dumpState() const {
  QJsonObject o;
  for (QLabel* l : {ray_, event_, cell_, interval_, dda_, nearest_, rule_, counters_}) o[l->objectName()] = l->text();
  if (treeBox_->isVisibleTo(const_cast<StatePanel*>(this)))
  {
    for (QLabel* l : {node_, crossing_}) o[l->objectName()] = l->text();
    QJsonArray rows;
    for (int r = 0; r < stack_->rowCount(); ++r) {
      QJsonArray row;
      for (int c = 0; c < 4; ++c) row.append(stack_->item(r, c) ? stack_->item(r, c)->text() : QString());
      rows.append(row);
    }
    o["stack"] = rows;
  }
  QJsonArray rows;
  for (int r = 0; r < mailbox_->rowCount(); ++r) {
    QJsonArray row;
    for (int c = 0; c < 4; ++c) row.append(mailbox_->cell(r, c));
    rows.append(row);
  }
  o["mailbox"] = rows;
  return o;
}

}  // namespace raystep::viz
