// The debugger's window: structure panel and image on the left, the 3D view in the middle, state panels and
// the event list on the right, the timeline along the bottom; for a kd-tree a dock below with the tree of
// nodes and the SAH inspector of the selected node. It owns the session and runs the heavy work
// (loading, structure build, render, heat map) on worker threads, so the window never freezes; in scripted
// mode the same work runs in place, one step after the other.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <vector>

#include <QFuture>
#include <QImage>
#include <QMainWindow>

class QDockWidget;
class QSplitter;
class QStackedWidget;

#include <string>

#include <glm/vec2.hpp>

#include "raystep/accel/structure_options.h"

namespace raystep {
struct Trace;
struct Lesson;
struct LessonState;
}  // namespace raystep

namespace raystep::viz {

class Session;
struct SceneData;
struct StructureData;
class StructurePanel;
class ImageView;
class SceneView;
class Timeline;
class StatePanel;
class EventList;
class TreeView;
class SahChart;
class LessonPane;
class Presenter;
class AaReportView;
class GridSweepView;
class BvolReportView;
class PixelInspector;
class CompareWindow;
class ClassroomLayout;
class FlatView;

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  MainWindow();
  ~MainWindow() override;

  // Scripted mode: work runs on the calling thread, and errors are thrown instead of shown.
  void setScripted(bool on) { scripted_ = on; }
  bool scripted() const { return scripted_; }
  // Work runs on the calling thread and its errors are thrown, without the rest of the scripted mode (times
  // stay in the status bar): entering a lesson step is one synchronous change of the whole state.
  void setWorkInPlace(bool on) { inPlace_ = on; }
  bool workInPlace() const { return inPlace_; }
  // Whether the file is a trace written by `raystep trace` (its format key), not a scene or a mesh.
  static bool isTraceFile(const QString& path);

  // Open a scene (.json scene or .obj mesh) or a trace written by `raystep trace`. Throws InputError in
  // scripted mode; shows the error in a dialog otherwise (the window keeps what it had).
  void openFile(const QString& path);
  // The GUI path of opening, in every mode: an error goes to a dialog (auto-closed in scripted mode).
  void openFileReportingErrors(const QString& path);
  void setStructureOptions(const std::string& accelName, const StructureOptions& o);
  // The structure panel's accelerator and options, as text; and those the current structure was built with
  // ("" : none built). Equal when a build would make the same structure again.
  QString structureOptionsKey() const;
  static QString structureKey(const std::string& accelName, const StructureOptions& o);
  // Builds the structure over the current scene on a worker thread and keeps it for buildStructure (the
  // presenter asks for the next step's while the class reads this one); nothing if it is kept or underway.
  void prefetchStructure(const std::string& accelName, const StructureOptions& o);
  void waitForPrefetches();  // blocks until every prefetch has finished (benchmarks of entering steps)
  QString builtStructureKey() const;
  void setImageSize(int w, int h);  // the picture's size (default: the scene's)
  void buildStructure();
  void renderPicture();
  void computeHeat();
  void tracePixel(int x, int y);
  // A 2D scene: the walk of the ray in the plane from `origin` along `direction` through the structure
  // (the 2D view's ray: dragged, given by --flat-ray, or the scene's own), traced at once. keepStep: the
  // step shown stays where it still exists (a drag), else the walk starts at its first event.
  void traceFlatRay(glm::vec2 origin, glm::vec2 direction, bool keepStep);
  // A 2D scene: the 2D view's figure at the current step as `raystep figure` writes it (.svg, .pdf, .png).
  void exportFigure(const QString& path);
  void exportTrace(const QString& path);
  // The SAH inspector: the dock with the tree and the chart; the selected node's curve as CSV (core's
  // columns).
  void showKdPanel();
  void hideKdPanel();
  bool kdPanelVisible() const;
  // The pixel inspector: the dock below with the traced pixel's samples (opened by a click on a pixel when
  // the picture is anti-aliased, and by a trace with a pixel section).
  void showPixelInspector();
  void hidePixelInspector();
  bool pixelInspectorVisible() const;
  // The picture and the heat map for the current structure, size, anti-aliasing and heat quantity: made again
  // only when one of these differs from what they were made for (entering a lesson step changes the pixel far
  // more often than the picture).
  void ensurePicture();
  void ensureHeat();
  void exportSahCsv(const QString& path);
  // Reports > ...: the anti-aliasing report and the grid sweep, each a window of its own (made when first
  // asked for). The sweep's slider rebuilds the grid here at the density it chooses.
  AaReportView* aaReportView();
  GridSweepView* gridSweepView();
  BvolReportView* bvolReportView();        // the kinds of bounding volumes
  void buildGridAtDensity(float density);  // the structure panel's grid options with density d, built

  // Presenter mode: the lesson pane docked on the right, beside the debugger, and the presenter that enters
  // the lesson's steps (none entered yet). A second lesson replaces the first.
  Presenter* openLesson(const Lesson& lesson);
  // File > Open lesson...: a damaged lesson goes to a dialog and the window stays as it was.
  void openLessonReportingErrors(const QString& path);
  Presenter* presenter() const { return presenter_; }
  LessonPane* lessonPane() const { return lessonPane_; }
  // Widens the window by the lesson pane, so that the debugger keeps the size it has without a lesson (a
  // step then shows what the same state shows in a window without the pane, pixel for pixel).
  void fitLessonPane();
  // Lets the user resize the pane (scripted runs keep it at the width fitLessonPane gave it).
  void releaseLessonPaneWidth();
  // A lesson at a presenter scale above 1: the step's figure takes the room (classroom_layout.h), the window
  // within the screen; at scale 1 (or without a lesson) the debugger's own layout.
  ClassroomLayout* classroom() const { return classroom_.get(); }
  void arrangeForStep(const LessonState& step);
  // Fonts, line widths and the 3D view's markers times `scale` (a lecture room wants 1.5).
  void setPresenterScale(double scale);
  double presenterScale() const { return scale_; }
  // An error in a dialog (auto-closed in scripted mode); the window goes on.
  void reportError(const QString& message) { showError(message); }

  // The same ray side by side (compare_window.h), a window of its own made when first asked for; comparePixel
  // builds the structures named (with the structure panel's options) over the current scene and shows pixel
  // (x, y)'s walks through them. Reports > Compare... picks them; each pixel clicked then is compared too.
  CompareWindow* compareWindow();
  CompareWindow* compareWindowIfMade() const { return compare_; }
  void comparePixel(const QStringList& kinds, int x, int y);
  // What Reports > Compare...'s dialog does on OK: the traced pixel (if any) compared through `kinds` now,
  // and each pixel clicked from then on while the window is open.
  void setCompareStructures(const QStringList& kinds);

  Session* session() const { return session_; }
  SceneView* sceneView() const { return sceneView_; }
  FlatView* flatView() const { return flatView_; }
  // The middle view's pixels: the 3D view's, or a 2D scene's 2D view's (screenshots, handouts).
  QImage grabMiddleView() const;
  ImageView* imageView() const { return imageView_; }
  Timeline* timeline() const { return timeline_; }
  StatePanel* statePanel() const { return statePanel_; }
  EventList* eventList() const { return eventList_; }
  StructurePanel* structurePanel() const { return structure_; }
  TreeView* treeView() const { return treeView_; }
  SahChart* sahChart() const { return sahChart_; }
  PixelInspector* pixelInspector() const { return pixelInspector_; }
  QString lastError() const { return lastError_; }

 private:
  void showError(const QString& message);
  QString took(const QString& what, double ms) const;
  // Runs work off the GUI thread (in place when scripted) and then done on the GUI thread; an InputError
  // thrown by work is shown (or rethrown when scripted).
  // A newer task of the same kind ("open", "build", "render", "heat") supersedes an older one.
  void runTask(const QString& kind, const QString& what, std::function<std::function<void()>()> work);
  void openScene(const QString& path);
  void openTrace(const QString& path);
  void showTrace(std::shared_ptr<const Trace> trace, const QString& path, double readMs);
  void buildMenus();
  void showSahCurve();  // records the selected node's curve off the GUI thread
  void showBvhSahCurve();    // the same for a BVH node (its binned curve)
  void showBspSahCurve();    // the same for a BSP node (its candidate planes by orientation)
  void drawPixelBackdrop();  // the scene inside the traced pixel, for the inspector (when not drawn yet)

  Session* session_;
  StructurePanel* structure_;
  ImageView* imageView_;
  SceneView* sceneView_;
  FlatView* flatView_;
  QStackedWidget* centreStack_;  // the 3D view, or the 2D view for a 2D scene
  Timeline* timeline_;
  StatePanel* statePanel_;
  EventList* eventList_;
  TreeView* treeView_;
  SahChart* sahChart_;
  AaReportView* aaReport_ = nullptr;
  GridSweepView* gridSweep_ = nullptr;
  BvolReportView* bvolReport_ = nullptr;
  QDockWidget* kdDock_;
  PixelInspector* pixelInspector_;
  QDockWidget* pixelDock_;
  QSplitter* rightSplit_ = nullptr;  // the state panel, the mailbox table, the event list
  QSplitter* leftSplit_ = nullptr;   // the structure panel, the image
  QSplitter* columns_ = nullptr;     // left, the 3D view, right
  QSplitter* kdSplit_ = nullptr;     // the tree | the SAH chart
  std::unique_ptr<ClassroomLayout> classroom_;
  QDockWidget* lessonDock_ = nullptr;
  LessonPane* lessonPane_ = nullptr;
  Presenter* presenter_ = nullptr;
  double scale_ = 1.0;
  int baseFontPt_ = 0;
  bool scripted_ = false;
  bool inPlace_ = false;
  QString pictureKey_, heatKey_;
  QString builtKey_;  // structureOptionsKey() of the current structure
  struct KeptStructure {
    std::shared_ptr<const SceneData> scene;
    QString key;
    std::shared_ptr<const StructureData> built;
  };
  std::vector<KeptStructure> kept_;  // the last structures built, for buildStructure to use again
  void keepStructure(const KeptStructure& k);
  struct Prefetch {
    std::shared_ptr<const SceneData> scene;
    QString key;
    QFuture<std::shared_ptr<const StructureData>> built;
  };
  std::vector<Prefetch> prefetches_;  // underway
  // what the picture and the heat map were made for (ensurePicture)
  QString pictureKeyNow() const;
  QString heatKeyNow() const;
  std::map<QString, int> generation_;  // per kind: results of superseded work are dropped
  int running_ = 0;
  int sizeW_ = 0, sizeH_ = 0;
  QString lastError_;
  CompareWindow* compare_ = nullptr;
  QStringList compareKinds_;  // picked in Reports > Compare...: a clicked pixel is compared through them
  std::map<QString, std::shared_ptr<const StructureData>> compareBuilt_;  // by kind, for the next click
};

}  // namespace raystep::viz
