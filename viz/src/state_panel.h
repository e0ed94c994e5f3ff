// The state panels, synced with the timeline. Grid: the current cell (i, j, k), its interval, tMax and
// tDelta per axis with the axis stepped next, the nearest hit so far, and the stopping rule
// "tmin(cell) > tmax(ray)" with its numbers when it ends the walk; the mailbox table; running counters.
// A tree section (stack, t*, tree view) goes beside the grid section when the kd-tree arrives.
#pragma once

#include <QJsonObject>
#include <QWidget>

class QLabel;
class QTableView;
class QGroupBox;

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

 private:
  void refresh();
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
  QLabel* stack_;
  QLabel* rule_;
  QLabel* counters_;
  QWidget* mailboxBox_;
  QTableView* mailboxView_;
  MailboxModel* mailbox_;
};

}  // namespace raystep::viz
