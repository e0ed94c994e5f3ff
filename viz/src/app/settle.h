// Letting the window system catch up: the X server confirms sizes and exposes asynchronously, so a layout
// measured, a window resized or a screenshot taken right after a change may see the old geometry. One round
// is processEvents and a 5 ms pause; the callers that script the window (--screenshot, --dump-state, the
// classroom layout) settle before they measure.
#pragma once

#include <QApplication>
#include <QThread>

namespace raystep::viz {

inline void settleWindowSystem(int rounds = 5) {
  for (int i = 0; i < rounds; ++i) {
    QApplication::processEvents();
    QThread::msleep(5);
  }
}

}  // namespace raystep::viz
