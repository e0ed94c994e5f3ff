// raystep-gui: the step-debugger. Everything lives in raystep_viz; this only starts Qt and VTK.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <QApplication>
#include <QCoreApplication>

#include "app/heartbeat.h"
#include "app/main_window.h"
#include "raystep/util/atomic_file.h"
#include "views/scene_view.h"
#include "app/script.h"

int main(int argc, char** argv) {
  raystep::remove_temporary_files_on_signals();
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      QCoreApplication app(argc, argv);  // the usage needs no display
      QCoreApplication::setApplicationName("raystep-gui");
      if (raystep::viz::printHelpIfAsked(QCoreApplication::arguments())) return 0;
    }
  // Qt aborts without a display, and VTK here has no off-screen OpenGL: say so plainly instead.
  const char* display = std::getenv("DISPLAY");
  const char* platform = std::getenv("QT_QPA_PLATFORM");
  if ((!display || !*display) && (!platform || !*platform)) {
    std::fprintf(stderr,
                 "error: raystep-gui needs an X server and DISPLAY is not set; run it on a desktop, or under "
                 "xvfb-run -a raystep-gui ...\n");
    return 2;
  }
  raystep::viz::SceneView::prepareSurfaceFormat();  // before QApplication, or VTK has no OpenGL context
  QApplication app(argc, argv);
  QApplication::setApplicationName("raystep-gui");
  raystep::viz::MainWindow window;
  raystep::viz::Heartbeat heartbeat;  // RAYSTEP_GUI_HEARTBEAT=SECONDS: load measurements (bench/README.md)
  int code = raystep::viz::runCommandLine(window, QApplication::arguments());
  return code >= 0 ? code : app.exec();
}
