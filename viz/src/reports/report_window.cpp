#include "reports/report_window.h"

#include <chrono>

#include <QApplication>
#include <QCloseEvent>
#include <QHBoxLayout>
#include <QLabel>
#include <QOpenGLWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QSaveFile>
#include <QThread>
#include <QVBoxLayout>
#include <QtConcurrent>

namespace raystep::viz {

ReportWindow::ReportWindow(QWidget* parent) : QWidget(parent, Qt::Window) {}

ReportWindow::~ReportWindow() {
  stopWorker();
}

namespace {

QLabel* selectableLabel(const QString& objectName) {
  auto* l = new QLabel;
  l->setObjectName(objectName);
  l->setWordWrap(true);
  l->setTextInteractionFlags(Qt::TextSelectableByMouse);
  return l;
}

}  // namespace

void ReportWindow::addHeader(QVBoxLayout* layout, const QString& prefix) {
  header_ = selectableLabel(prefix + "Header");
  layout->addWidget(header_);
}

void ReportWindow::addRunCancel(QHBoxLayout* options, const QString& prefix) {
  run_ = new QPushButton(tr("Run"));
  run_->setObjectName(prefix + "Run");
  cancelButton_ = new QPushButton(tr("Cancel"));
  cancelButton_->setObjectName(prefix + "Cancel");
  cancelButton_->setEnabled(false);
  options->addWidget(run_);
  options->addWidget(cancelButton_);
  connect(run_, &QPushButton::clicked, this, [this] { start(); });
  connect(cancelButton_, &QPushButton::clicked, this, &ReportWindow::cancel);
}

void ReportWindow::addProgress(QVBoxLayout* layout, const QString& prefix) {
  progress_ = new QProgressBar;
  progress_->setObjectName(prefix + "Progress");
  progress_->setRange(0, 1000);
  progress_->setValue(0);
  layout->addWidget(progress_);
}

void ReportWindow::addStatus(QVBoxLayout* layout, const QString& prefix) {
  status_ = selectableLabel(prefix + "Status");
  layout->addWidget(status_);
}

bool ReportWindow::saveChart(const QString& path) {
  renderNow();
  QSaveFile file(path);
  return file.open(QIODevice::WriteOnly) && chartWidget()->grabFramebuffer().save(&file, "PNG") &&
         file.commit();
}

QJsonObject ReportWindow::dumpCommon() const {
  QJsonObject o;
  o["state"] = state_;
  o["error"] = error_;
  o["visible"] = isVisible();
  return o;
}

void ReportWindow::stopWorker() {
  cancel_ = true;
  future_.waitForFinished();
}

void ReportWindow::stopForNewRun() {
  if (running_) {
    cancel();
    future_.waitForFinished();
    QApplication::processEvents();  // the old run's last rows and its end
  }
  error_.clear();
}

int ReportWindow::beginRun(const QString& status) {
  state_ = "running";
  running_ = true;
  cancel_ = false;
  rowsDone_ = 0;
  run_->setEnabled(false);
  cancelButton_->setEnabled(true);
  status_->setText(status);
  return ++generation_;
}

void ReportWindow::toGui(int gen, std::function<void()> f) {
  QMetaObject::invokeMethod(
      this,
      [this, gen, f] {
        if (gen == generation_) f();
      },
      Qt::QueuedConnection);
}

void ReportWindow::rowDoneOnWorker() {
  if (++rowsDone_ == cancelAfterRows_) cancel_ = true;  // as a click on Cancel right after this row
}

void ReportWindow::runOnWorker(int gen, std::function<void()> work,
                               std::function<void(const QString&, const QString&)> finish) {
  future_ = QtConcurrent::run([this, gen, work, finish] {
    QString state = "done", error;
    try {
      work();
      if (cancel_) state = "cancelled";
    } catch (const std::exception& e) {
      state = "failed";
      error = QString::fromStdString(e.what());
    }
    toGui(gen, [finish, state, error] { finish(state, error); });
  });
}

void ReportWindow::endRun(const QString& state, const QString& error) {
  running_ = false;
  state_ = state;
  error_ = error;
  run_->setEnabled(true);
  cancelButton_->setEnabled(false);
}

QString ReportWindow::refuseStart(const std::exception& e) {
  error_ = QString::fromStdString(e.what());
  state_ = "failed";
  status_->setText(tr("<span style='color:#b00'>%1</span>").arg(error_.toHtmlEscaped()));
  return error_;
}

void ReportWindow::closeEvent(QCloseEvent* event) {
  cancel();
  QWidget::closeEvent(event);
}

void ReportWindow::cancel() {
  if (!running_) return;
  cancel_ = true;
  status_->setText(cancellingText_);
}

bool ReportWindow::waitForFinished(int timeoutMs) {
  auto t0 = std::chrono::steady_clock::now();
  while (running_) {
    QApplication::processEvents(QEventLoop::AllEvents, 20);
    QThread::msleep(5);
    if (std::chrono::steady_clock::now() - t0 > std::chrono::milliseconds(timeoutMs)) return false;
  }
  QApplication::processEvents();
  return true;
}

}  // namespace raystep::viz
