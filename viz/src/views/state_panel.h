// The state panels, synced with the timeline. Grid: the current cell (i, j, k), its interval, tMax and
// tDelta per axis with the axis stepped next, the nearest hit so far, and the stopping rule
// "tmin(cell) > tmax(ray)" with its numbers when it ends the walk. Tree (kd-tree): the current node, its t*
// and which children the ray crosses, and the stack as a table (node, depth, t_min, t_max) that grows with
// push and shrinks with pop. BVH: each child's [t_near, t_far] or miss, the child entered first (the nearer),
// what was pushed, and the stack. All: the "Why" line, the mailbox table, running counters.
#pragma once

#include <QJsonObject>
#include <QWidget>

#include "raystep/replay/replay_state.h"

class QLabel;
class QTableView;
class QTableWidget;
class QGroupBox;

namespace raystep {
struct TracedRay;
}

namespace raystep::viz {

class Session;
class MailboxModel;

class StatePanel : public QWidget {
  Q_OBJECT
 public:
  explicit StatePanel(Session* session, QWidget* parent = nullptr);
  // Every text shown, and the mailbox table, for the scripted mode's --dump-state.
  QJsonObject dumpState() const;
  // The mailbox table, which the window places on its own (it wants height).
  QWidget* mailboxWidget() const { return mailboxBox_; }
  // The stack table's rows follow the presenter scale (their height was set for the desk's font).
  void setScale(double scale);
  // The quiz asks what the walk does next: the Why text and the 3D-DDA's next axis are hidden until the
  // answer is revealed.
  void setConceal(bool on);

 private:
  void refresh();
  void refreshTree(const TracedRay& ray, const replay::ReplayState& s);
  void refreshOctreeChildren(const TracedRay& r, const replay::ReplayState& s);
  void refreshBvhChildren(const TracedRay& ray, const replay::ReplayState& s);
  Session* session_;
  QLabel* ray_;
  QLabel* event_;
  QGroupBox* gridBox_;
  QLabel* cell_;
  QLabel* interval_;
  QLabel* dda_;  // tMax / tDelta table, next axis marked
  QLabel* nearest_;
  QGroupBox* treeBox_;
  QLabel* node_;
  QLabel* stackTitle_;
  QLabel* crossing_;  // kd: t* and the children crossed; BVH: each child's box test and the order chosen
  QLabel* crossingTitle_;
  QGroupBox* mailBoxGroup_;
  QTableWidget* stack_;
  QLabel* rule_;
  QLabel* counters_;
  QWidget* mailboxBox_;
  QTableView* mailboxView_;
  MailboxModel* mailbox_;
  int rowHeight_ = 18;
  bool conceal_ = false;
};

}  // namespace raystep::viz
