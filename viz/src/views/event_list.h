// The event list: every event of the current ray, one line each, the current one selected and kept in view.
// A model over the trace (lines made on demand), so 100,000 events open at once. Clicking a row goes there.
#pragma once

#include <QWidget>

class QListView;

namespace raystep::viz {

class Session;
class EventModel;

class EventList : public QWidget {
  Q_OBJECT
 public:
  explicit EventList(Session* session, QWidget* parent = nullptr);
  int currentRow() const;
  void setScale(double scale);
  // The quiz: the events after `step` are not shown until the answer is revealed (-1: all shown).
  void setConcealAfter(int step);  // the fixed-width font, times the presenter scale

 protected:
  // The list shrinks when a panel opens below it: the current event is brought back into view.
  void resizeEvent(QResizeEvent* event) override;

 private:
  void sync();
  Session* session_;
  QListView* view_;
  EventModel* model_;
};

}  // namespace raystep::viz
