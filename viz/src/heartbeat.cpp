#include "heartbeat.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include <QCoreApplication>
#include <QTimer>

namespace raystep::viz {

namespace {

constexpr int kBeatMs = 10;
constexpr double kStallMs = 100;

double secondsFromEnvironment() {
  const char* v = std::getenv("RAYSTEP_GUI_HEARTBEAT");
  return v && *v ? std::atof(v) : 0.0;
}

// The peak resident memory so far, from /proc (Linux), in MiB; -1 when unknown.
double peakRssMiB() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
  return -1;
}

}  // namespace

bool Heartbeat::enabled() {
  return secondsFromEnvironment() > 0;
}

Heartbeat::Heartbeat(QObject* parent) : QObject(parent), seconds_(secondsFromEnvironment()) {
  if (!(seconds_ > 0)) return;
  start_ = last_ = std::chrono::steady_clock::now();
  timer_ = new QTimer(this);
  timer_->setTimerType(Qt::PreciseTimer);
  connect(timer_, &QTimer::timeout, this, &Heartbeat::beat);
  timer_->start(kBeatMs);
}

void Heartbeat::beat() {
  const auto now = std::chrono::steady_clock::now();
  const double gap = std::chrono::duration<double, std::milli>(now - last_).count() - kBeatMs;
  const double at = std::chrono::duration<double>(now - start_).count();
  last_ = now;
  if (gap >= kStallMs) {
    ++stalls_;
    std::fprintf(stderr, "heartbeat: the GUI thread was busy %.0f ms (until %.1f s)\n", gap, at);
  }
  if (gap > longestMs_) {
    longestMs_ = gap;
    longestAt_ = at;
  }
  if (at >= seconds_) {
    report("time is up");
    QCoreApplication::exit(0);
  }
}

void Heartbeat::report(const char* why) {
  timer_->stop();
  std::fprintf(
      stderr,
      "heartbeat: %s after %.1f s: longest GUI-thread stall %.0f ms (until %.1f s), %d stalls of %.0f ms "
      "or more; peak memory %.0f MiB\n",
      why, seconds_, longestMs_, longestAt_, stalls_, kStallMs, peakRssMiB());
}

}  // namespace raystep::viz
