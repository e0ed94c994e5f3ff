// A watch on the GUI thread for load measurements (RAYSTEP_GUI_HEARTBEAT=SECONDS): a timer that should fire
// every 10 ms notes each gap of 100 ms or more (the GUI thread was busy: the window did not answer), and
// after SECONDS quits with the longest gap and the process's peak memory. Work on the workers (build, render,
// heat map) must not show up here; only what the GUI thread does itself.
#pragma once

#include <chrono>

#include <QObject>

class QTimer;

namespace raystep::viz {

class Heartbeat : public QObject {
  Q_OBJECT
 public:
  // Started when RAYSTEP_GUI_HEARTBEAT holds a number of seconds > 0; else does nothing.
  explicit Heartbeat(QObject* parent = nullptr);
  static bool enabled();

 private:
  void beat();
  void report(const char* why);
  QTimer* timer_ = nullptr;
  std::chrono::steady_clock::time_point start_, last_;
  double lastCpu_ = 0;                    // the GUI thread's CPU time at the last beat, ms
  double longestMs_ = 0, longestAt_ = 0;  // the most CPU the GUI thread spent between two beats
  double longestGapMs_ = 0;               // the longest gap between beats (the machine's load too)
  int stalls_ = 0;
  double seconds_ = 0;
};

}  // namespace raystep::viz
