// The anti-aliasing report in the debugger (lecture: "anti-aliasing: how many rays for how little error"):
// core's run_aa_report on the current scene and structure, on a worker thread, its rows drawn as they come
// on log-log axes, RMSE against rays per pixel (or against time), one line per method family (regular,
// jitter, random, adaptive; none as a point), the slopes the theory predicts at edges (N^-1/2, N^-3/4)
// dashed, the reference's own error as a floor; a table of the rows below. VTK stays inside the .cpp.
#pragma once

#include <memory>

#include <QJsonObject>
#include <QString>

#include "raystep/report/aa_report.h"
#include "reports/report_window.h"

class QLabel;
class QLineEdit;
class QSpinBox;
class QComboBox;
class QTabBar;
class QTableWidget;

namespace raystep::viz {

class Session;

class AaReportView : public ReportWindow {
  Q_OBJECT
 public:
  explicit AaReportView(Session* session, QWidget* parent = nullptr);
  ~AaReportView() override;  // cancels a running report and waits for its current render

  // The options of the next run; methods: comma-separated specs ("" : the defaults), size 0: the scene's,
  // at most 128 pixels on its long side (the header says so).
  void setMethods(const QString& methods);
  void setReference(const QString& reference);  // "auto", "exact" or "jitter:K"
  void setReportSize(int width, int height);
  void setSeeds(int seeds);
  // Runs the report on the session's scene and structure (any running one is cancelled first). Bad options:
  // the error is shown in the view and returned (empty: started). Cancel, the state: ReportWindow.
  QString start() override;
  // "rays" (RMSE against rays per pixel) or "time" (against seconds per render).
  void setXAxis(const QString& axis);
  QString xAxis() const;

  // What the report produced so far (the GUI thread's copy).
  const AaReport& report() const { return report_; }
  // The points as plotted (per series, and in the order the rows came), the rows, the state (JSON).
  QJsonObject dumpState() const;
  void renderNow() override;  // saveChart: ReportWindow

 protected:
  QOpenGLWidget* chartWidget() const override;

 private:
  void addRow(const AaReport& soFar, const AaReportRow& row);
  void done(const AaReport& report, const QString& state, const QString& error);
  void redraw();
  void updateHeader();

  struct Impl;
  std::unique_ptr<Impl> d_;
  Session* session_;
  AaReport report_;
  QString sceneName_, structureName_;
  QString reducedFrom_;  // the scene's size, when the report renders it smaller (no Size given)

  QLineEdit* methods_;
  QComboBox* reference_;
  QLineEdit* size_;
  QSpinBox* seeds_;
  QTabBar* axisTabs_;
  QTableWidget* table_;
};

}  // namespace raystep::viz
