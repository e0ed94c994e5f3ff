// The structure panel: which acceleration structure and its build parameters. Grid: density d (in
// max(nx, ny, nz) = d * cbrt(n)) or an explicit resolution, exact (triangle-box overlap) or bounding-box
// insertion. The kd-tree section (t_i, t_t, empty bonus, SAH or median, max depth) is laid out but disabled
// until the kd-tree core is merged. The build itself runs off the GUI thread (the main window does it).
#pragma once

#include <QWidget>

#include "raystep/accel/grid.h"

class QCheckBox;
class QDoubleSpinBox;
class QGroupBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QComboBox;
class QSpinBox;

namespace raystep::viz {

class StructurePanel : public QWidget {
  Q_OBJECT
 public:
  explicit StructurePanel(QWidget* parent = nullptr);
  GridOptions gridOptions() const;
  void setGridOptions(const GridOptions& o);
  void setBusy(bool busy);  // a moving bar while work runs in the background
  void setInfo(const QString& text);

 Q_SIGNALS:
  void buildRequested();

 private:
  QComboBox* accel_;
  QDoubleSpinBox* density_;
  QCheckBox* explicitRes_;
  QSpinBox* res_[3];
  QComboBox* insert_;
  QPushButton* build_;
  QProgressBar* progress_;
  QLabel* info_;
  QGroupBox* kd_;
};

}  // namespace raystep::viz
