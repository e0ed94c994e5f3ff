#include "app/heartbeat.h"

#include <time.h>

#include <algorithm>
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

// CPU time this thread has used, in ms: a gap in which the GUI thread used little CPU was the machine's load
// (the thread waited for a core), not the debugger's work.
double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

}  // namespace

bool Heartbeat::enabled() {
  return secondsFromEnvironment() > 0;
}

Heartbeat::Heartbeat(QObject* parent) : QObject(parent), seconds_(secondsFromEnvironment()) {
  if (!(seconds_ > 0)) return;
  start_ = last_ = std::chrono::steady_clock::now();
  lastCpu_ = threadCpuMs();
  timer_ = new QTimer(this);
  timer_->setTimerType(Qt::PreciseTimer);
  connect(timer_, &QTimer::timeout, this, &Heartbeat::beat);
  timer_->start(kBeatMs);
}

void Heartbeat::beat() {
  const auto now = std::chrono::steady_clock::now();
  const double gap = std::chrono::duration<double, std::milli>(now - last_).count() - kBeatMs;
  const double at = std::chrono::duration<double>(now - start_).count();
  const double cpu = threadCpuMs(), busy = cpu - lastCpu_;
  last_ = now;
  lastCpu_ = cpu;
  if (gap >= kStallMs)
    std::fprintf(stderr,
                 "heartbeat: no beat for %.0f ms (until %.1f s), the GUI thread working %.0f ms of it\n", gap,
                 at, busy);
  if (busy >= kStallMs) ++stalls_;
  if (busy > longestMs_) {
    longestMs_ = busy;
    longestAt_ = at;
  }
  longestGapMs_ = std::max(longestGapMs_, gap);
  if (at >= seconds_) {
    report("time is up");
    QCoreApplication::exit(0);
  }
}

void Heartbeat::report(const char* why) {
  timer_->stop();
  std::fprintf(
      stderr,
      "heartbeat: %s after %.1f s: the GUI thread's longest stretch of work %.0f ms (until %.1f s), %d of "
      "%.0f ms or more; longest gap between beats %.0f ms; peak memory %.0f MiB\n",
      why, seconds_, longestMs_, longestAt_, stalls_, kStallMs, longestGapMs_, peakRssMiB());
}

}  // namespace raystep::viz
