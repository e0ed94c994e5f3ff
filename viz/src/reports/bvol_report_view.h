// The kinds of bounding volumes in the debugger (lecture: "many different kinds of bounding volumes", and the
// cost T = B + p n I of one volume per object): core's run_bvol_report on the current scene, on a worker
// thread, drawn as bars per kind (box, sphere, 14-DOP, oriented box): the volumes a ray enters and those it
// enters in vain (false positives), the false-positive rate, the primitive tests and the time per ray, with
// every column in a table. The volumes record no walk, so this is how a lesson shows them. VTK stays inside
// the .cpp.
#pragma once

#include <memory>
#include <vector>

#include <QJsonObject>
#include <QString>

#include "raystep/report/bvol_report.h"
#include "reports/report_window.h"

class QTableWidget;

namespace raystep::viz {

class Session;

class BvolReportView : public ReportWindow {
  Q_OBJECT
 public:
  explicit BvolReportView(Session* session, QWidget* parent = nullptr);
  ~BvolReportView() override;  // waits for a running report

  // Runs the report on the session's scene (one ray per pixel, at most 160 on a side); the error (empty:
  // started) is also shown in the view. The state: ReportWindow.
  QString start() override;

  const std::vector<BvolReportRow>& rows() const { return rows_; }
  QJsonObject dumpState() const;
  void renderNow() override;  // saveChart: ReportWindow

 protected:
  QOpenGLWidget* chartWidget() const override;

 private:
  void done(const std::vector<BvolReportRow>& rows, const QString& state, const QString& error);
  void fillTable();
  void redraw();

  struct Impl;
  std::unique_ptr<Impl> d_;
  Session* session_;
  std::vector<BvolReportRow> rows_;
  QString sceneName_;
  QTableWidget* table_;
};

}  // namespace raystep::viz
