// raystep-gui: the step-debugger. Everything lives in raystep_viz; this only starts Qt and VTK.
#include <QApplication>

#include "main_window.h"
#include "scene_view.h"
#include "script.h"

int main(int argc, char** argv) {
  raystep::viz::SceneView::prepareSurfaceFormat();  // before QApplication, or VTK has no OpenGL context
  QApplication app(argc, argv);
  QApplication::setApplicationName("raystep-gui");
  raystep::viz::MainWindow window;
  int code = raystep::viz::runCommandLine(window, QApplication::arguments());
  return code >= 0 ? code : app.exec();
}
