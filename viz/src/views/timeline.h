// The timeline: step forward and back, jump to the next or previous event of a kind (cell, push/pop,
// primitive test, mailbox hit, the hit), play and pause at a chosen speed, and a slider over all events.
// Keys (window-wide): Right/Left step, Space plays or pauses, Home/End go to the first/last event.
#pragma once

#include <vector>

#include <QWidget>

#include "raystep/record/events.h"

class QComboBox;
class QLabel;
class QToolButton;
class QSlider;
class QSpinBox;
class QTimer;
class QHBoxLayout;
class QShortcut;

namespace raystep::viz {

class Session;

class Timeline : public QWidget {
  Q_OBJECT
 public:
  explicit Timeline(Session* session, QWidget* parent = nullptr);

  // A jump target: "cell", "pushpop", "prim_test", "mailbox_hit", "hit", "node", "leaf".
  bool jump(const QString& kind, bool forward);
  void setPlaying(bool on);
  bool playing() const;
  static std::vector<EventType> typesOf(const QString& kind);
  // In a lesson the plain arrows, Home and End move between steps (a clicker sends them): the walk's keys
  // become Shift+Right/Shift+Left (and . and ,), Shift+Home/Shift+End.
  void setLessonKeys(bool on);
  // Compact (presenter scales): "Jump to" and "Ray" move to the slider's row.
  void setCompact(bool on);

 private:
  void refresh();
  // Offer the walk's own unit first in "Jump to": the next node in a tree, the next cell in a grid.
  void offerUnit(bool tree);
  Session* session_;
  QSlider* slider_;
  QLabel* position_;
  QComboBox* kind_;
  QComboBox* ray_;
  QToolButton* play_;
  QSpinBox* speed_;
  QTimer* timer_;
  QWidget* jumpBox_;
  QHBoxLayout* row2_;
  QShortcut* forwardKey_;
  QShortcut* backKey_;
  QShortcut* firstKey_;
  QShortcut* lastKey_;
  QShortcut* periodKey_;
  QShortcut* commaKey_;
};

}  // namespace raystep::viz
