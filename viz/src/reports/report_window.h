// What the report windows (AaReportView, GridSweepView) share: a core report run on a worker thread, its rows
// and progress handed to the GUI thread, Run and Cancel, the state ("idle", "running", "done", "cancelled",
// "failed") and the last error. Each view keeps its own options, chart and rows.
#pragma once

#include <atomic>
#include <exception>
#include <functional>

#include <QFuture>
#include <QJsonObject>
#include <QString>
#include <QWidget>

class QHBoxLayout;
class QLabel;
class QOpenGLWidget;
class QProgressBar;
class QPushButton;
class QVBoxLayout;

namespace raystep::viz {

class ReportWindow : public QWidget {
  Q_OBJECT
 public:
  explicit ReportWindow(QWidget* parent = nullptr);  // a window of its own (Qt::Window)
  ~ReportWindow() override;  // cancels a running report and waits for its current step

  // Runs the report (a running one is cancelled first); bad options: the error, also shown (empty: started).
  virtual QString start() = 0;
  virtual void renderNow() = 0;         // draws the chart now
  bool saveChart(const QString& path);  // the chart alone, as PNG (atomically)

  void cancel();  // as the Cancel button: the report stops after its current step
  bool running() const { return running_; }
  // Scripted mode: processes events until the report has finished (false after timeoutMs).
  bool waitForFinished(int timeoutMs);
  // Tests: cancel as the Cancel button does, on the worker right after the report's n-th row.
  void setCancelAfterRows(int n) { cancelAfterRows_ = n; }
  QString state() const { return state_; }  // "idle", "running", "done", "cancelled", "failed"
  QString lastError() const { return error_; }

 Q_SIGNALS:
  void finished();

 protected:
  void closeEvent(QCloseEvent* event) override;  // closing the window cancels a run under way

  // The widgets every report window has, named prefix + "Header", "Run", "Cancel", "Progress" (0..1000),
  // "Status"; Run starts, Cancel cancels.
  void addHeader(QVBoxLayout* layout, const QString& prefix);
  void addRunCancel(QHBoxLayout* options, const QString& prefix);
  void addProgress(QVBoxLayout* layout, const QString& prefix);
  void addStatus(QVBoxLayout* layout, const QString& prefix);

  virtual QOpenGLWidget* chartWidget() const = 0;
  QJsonObject dumpCommon() const;  // what every view's --dump-state has: state, error, visible

  // start()'s steps: cancel and wait out a run under way (its last rows and end delivered), clear the error.
  void stopForNewRun();
  // The run begins: Run disabled, Cancel enabled, status shown; returns the run's generation.
  int beginRun(const QString& status);
  // On the worker: work runs the core report (it may throw); finish(state, error) then runs on the GUI
  // thread, unless a newer run has started.
  void runOnWorker(int gen, std::function<void()> work,
                   std::function<void(const QString& state, const QString& error)> finish);
  // From the worker: f runs on the GUI thread, unless a newer run than gen has started by then.
  void toGui(int gen, std::function<void()> f);
  // On the worker, after each row: counts it for setCancelAfterRows.
  void rowDoneOnWorker();
  // The end of a run on the GUI thread (Run enabled again), or bad options refused by start().
  void endRun(const QString& state, const QString& error);
  QString refuseStart(const std::exception& e);
  // Destructors of the views call it first: the worker must not outlive what its callbacks reach.
  void stopWorker();

  std::atomic<bool> cancel_{false};
  QString cancellingText_;  // the status while cancelling, in the view's words
  QLabel* header_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QPushButton* run_ = nullptr;
  QPushButton* cancelButton_ = nullptr;
  QLabel* status_ = nullptr;

 private:
  QString state_ = "idle", error_;
  bool running_ = false;
  std::atomic<int> cancelAfterRows_{0};
  std::atomic<int> rowsDone_{0};
  QFuture<void> future_;
  int generation_ = 0;
};

}  // namespace raystep::viz
