#include "state_panel.h"

#include <cmath>

#include <QAbstractTableModel>
#include <QFormLayout>
#include <QGroupBox>
#include <QHeaderView>
#include <QJsonArray>
#include <QLabel>
#include <QTableView>
#include <QVBoxLayout>

#include "replay.h"
#include "session.h"

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
  void setEntries(const std::vector<MailboxEntry>* entries) {
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
    static const char* names[] = {"prim", "tested in cell", "result", "skips"};
    return names[section];
  }
  QVariant data(const QModelIndex& index, int role) const override {
    if (!entries_ || role != Qt::DisplayRole) return {};
    return cell(index.row(), index.column());
  }
  QString cell(int row, int col) const {
    const MailboxEntry& m = (*entries_)[size_t(row)];
    switch (col) {
      case 0: return QString::number(m.prim);
      case 1:
        return m.testedInCellEvent < 0 ? QString("-") : QString("(%1,%2,%3)").arg(m.cell[0]).arg(m.cell[1]).arg(m.cell[2]);
      case 2: return m.hit ? QString("hit t=%1").arg(num(m.t)) : QString("miss");
      default: return QString::number(m.skips);
    }
  }

 private:
  const std::vector<MailboxEntry>* entries_ = nullptr;
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

  gridBox_ = new QGroupBox(tr("Grid: 3D-DDA"));
  auto* form = new QFormLayout(gridBox_);
  cell_ = label("cellLabel");
  interval_ = label("intervalLabel");
  dda_ = label("ddaLabel");
  nearest_ = label("nearestLabel");
  form->addRow(tr("cell (i,j,k)"), cell_);
  form->addRow(tr("[t_enter, t_exit]"), interval_);
  form->addRow(dda_);
  form->addRow(tr("nearest hit"), nearest_);
  layout->addWidget(gridBox_);

  // Trees (kd-tree): the current node and the stack, shown when the trace has tree events.
  treeBox_ = new QGroupBox(tr("Tree: stack traversal"));
  auto* treeForm = new QFormLayout(treeBox_);
  node_ = label("nodeLabel");
  stack_ = label("stackLabel");
  treeForm->addRow(tr("node"), node_);
  treeForm->addRow(tr("stack (top first)"), stack_);
  treeBox_->hide();
  layout->addWidget(treeBox_);

  auto* ruleBox = new QGroupBox(tr("Why"));
  auto* ruleLayout = new QVBoxLayout(ruleBox);
  rule_ = label("ruleLabel");
  rule_->setTextFormat(Qt::PlainText);
  ruleLayout->addWidget(rule_);
  layout->addWidget(ruleBox);

  auto* counterBox = new QGroupBox(tr("Counters so far"));
  auto* counterLayout = new QVBoxLayout(counterBox);
  counters_ = label("countersLabel");
  counterLayout->addWidget(counters_);
  layout->addWidget(counterBox);

  auto* mailBox = new QGroupBox(tr("Mailbox: primitives tested for this ray"));
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
  refresh();
}

void StatePanel::refresh() {
  const TracedRay* r = session_->ray();
  const ReplayState& s = session_->state();
  mailbox_->setEntries(r ? &s.mailbox : nullptr);
  if (!r || !s.event) {
    ray_->setText(tr("<i>No ray yet. Click a pixel in the image, or open a trace.</i>"));
    for (QLabel* l : {event_, cell_, interval_, dda_, nearest_, rule_, counters_, node_, stack_}) l->clear();
    return;
  }
  bool tree = false;
  for (const Event& e : r->events)
    if (e.type == EventType::node || e.type == EventType::push || e.type == EventType::pop || e.type == EventType::leaf) {
      tree = true;
      break;
    }
  treeBox_->setVisible(tree);
  gridBox_->setVisible(!tree || s.cellEvent >= 0);
  if (tree) {
    if (s.nodeEvent >= 0) {
      const Event& n = r->events[size_t(s.nodeEvent)];
      node_->setText(tr("<b>%1</b> (%2), depth %3, [t_min, t_max] = [%4, %5]")
                         .arg(n.node)
                         .arg(event_type_name(n.type))
                         .arg(n.depth)
                         .arg(num(n.t_min_node), num(n.t_max_node)));
    } else {
      node_->setText(tr("<i>not in the tree yet</i>"));
    }
    QString st;
    for (auto it = s.stack.rbegin(); it != s.stack.rend(); ++it)
      st += tr("node %1 (depth %2) [%3, %4]<br>").arg(it->node).arg(it->depth).arg(num(it->tMin), num(it->tMax));
    stack_->setText(st.isEmpty() ? tr("<i>empty</i>") : st);
  }
  ray_->setText(tr("<b>Ray</b> %1, depth %2%3: o = (%4, %5, %6), d = (%7, %8, %9)")
                    .arg(ray_kind_name(r->kind))
                    .arg(r->depth)
                    .arg(r->has_pixel ? tr(", pixel (%1, %2)").arg(r->pixel[0]).arg(r->pixel[1]) : QString())
                    .arg(num(r->ray.origin.x), num(r->ray.origin.y), num(r->ray.origin.z))
                    .arg(num(r->ray.direction.x), num(r->ray.direction.y), num(r->ray.direction.z)));
  event_->setText(tr("<b>Event</b> %1").arg(QString::fromStdString(describeEvent(*s.event)).toHtmlEscaped()));

  if (s.cellEvent >= 0) {
    const Event& c = r->events[size_t(s.cellEvent)];
    cell_->setText(QString("<b>(%1, %2, %3)</b>").arg(c.cell[0]).arg(c.cell[1]).arg(c.cell[2]));
    interval_->setText(QString("[%1, %2]").arg(num(c.t_enter), num(c.t_exit)));
    QString t = "<table cellspacing=4><tr><th></th><th>x</th><th>y</th><th>z</th></tr><tr><td>tMax</td>";
    for (int a = 0; a < 3; ++a)
      t += a == c.next_axis ? QString("<td><b><u>%1</u></b></td>").arg(num(c.t_max[a]))
                            : QString("<td>%1</td>").arg(num(c.t_max[a]));
    t += "</tr><tr><td>tDelta</td>";
    for (int a = 0; a < 3; ++a) t += QString("<td>%1</td>").arg(num(c.t_delta[a]));
    t += QString("</tr></table>next axis: <b>%1</b>%2")
             .arg(axisName(c.next_axis))
             .arg(c.next_axis >= 0 ? tr(" (smallest tMax)") : tr(" (the walk ends in this cell)"));
    dda_->setText(t);
  } else {
    cell_->setText(tr("<i>not in the grid yet</i>"));
    interval_->clear();
    dda_->clear();
  }
  if (s.nearestPrim >= 0)
    nearest_->setText(tr("prim %1 at t = %2 <b>%3</b>")
                          .arg(s.nearestPrim)
                          .arg(num(s.nearestT))
                          .arg(s.accepted ? tr("(accepted)") : s.deferred ? tr("(deferred: beyond the cell's exit)")
                                                                          : tr("(candidate)")));
  else nearest_->setText(s.ended ? tr("none: a miss") : tr("none yet"));
  rule_->setText(QString::fromStdString(explainRule(*r, s)));
  const RayCounters& k = s.counters;
  counters_->setText(tr("cells %1 &nbsp; primitive tests %2 &nbsp; hits %3 &nbsp; mailbox hits %4")
                         .arg(k.cells)
                         .arg(k.prim_tests)
                         .arg(k.prim_hits)
                         .arg(k.mailbox_hits) +
                     (k.nodes || k.pushes || k.pops
                          ? tr("<br>nodes %1 &nbsp; pushes %2 &nbsp; pops %3").arg(k.nodes).arg(k.pushes).arg(k.pops)
                          : QString()));
  if (s.event->type == EventType::prim_test) mailboxView_->scrollToBottom();
}

QJsonObject StatePanel::dumpState() const {
  QJsonObject o;
  for (QLabel* l : {ray_, event_, cell_, interval_, dda_, nearest_, rule_, counters_}) o[l->objectName()] = l->text();
  if (treeBox_->isVisibleTo(const_cast<StatePanel*>(this)))
    for (QLabel* l : {node_, stack_}) o[l->objectName()] = l->text();
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
