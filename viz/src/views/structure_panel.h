// The structure panel: which acceleration structure and its build parameters. Grid: density d (in
// max(nx, ny, nz) = d * cbrt(n)) or an explicit resolution, exact (triangle-box overlap) or bounding-box
// insertion; the info line says when the density rule's resolution was coarsened to the reference budget.
// kd-tree: t_i, t_t (the SAH's costs), empty bonus, SAH or spatial-median builder, max depth (0:
// max(8, 1.2 log2 N), with an empty bonus pbrt's 8 + 1.3 log2 N), leaf size, mailboxes; an edit of a kd cost
// rebuilds at once. BVH: the builder (binned SAH, full sweep SAH, object median, or the wide BVH4/BVH8
// collapsed from the binned one), t_i and t_t, bins per axis, leaf size, max depth, and the binary walk's
// order (nearer child by entry distance or by the ray's direction on the split axis). Octree: the leaf size K
// and the depth limit. General BSP tree: the candidate directions (k-DOP, the primitives' own planes, both)
// and positions per direction, with the kd-tree's costs, depth limit and leaf size. The build itself runs
// off the GUI thread (the main window does it).
#pragma once

#include <QWidget>

#include <string>

#include "raystep/accel/structure_options.h"

class QCheckBox;
class QDoubleSpinBox;
class QGroupBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QComboBox;
class QSpinBox;
class QTimer;
class QToolButton;

namespace raystep::viz {

class StructurePanel : public QWidget {
  Q_OBJECT
 public:
  explicit StructurePanel(QWidget* parent = nullptr);
  // The accelerator's name for make_accelerator: "grid", "kd" (SAH), "kd-median", "bvh", "bvh-sweep",
  // "bvh-median", "bvh4", "bvh8", "octree" or "bsp".
  std::string accelName() const;
  StructureOptions options() const;
  void setStructure(const std::string& accelName, const StructureOptions& o);
  void setBusy(bool busy);  // a moving bar while work runs in the background
  void setInfo(const QString& text);
  QString info() const;  // what the info line below the options says (the state dump has it)
  bool costsEditPending() const;  // an edited kd cost waits for the spin box to rest
  // Compact (presenter scales): the info line only, the options behind an "Options" button; a lesson sets
  // them, and at 1.5 times the size they would take a third of a projector's width.
  void setCompact(bool on);

 Q_SIGNALS:
  void buildRequested();
  // The user changed t_i, t_t or the empty bonus (sent once the value has rested for a moment): the kd-tree
  // is rebuilt with them, without a click on Build.
  void kdCostsEdited();

 private:
  QComboBox* accel_;
  QDoubleSpinBox* density_;
  QCheckBox* explicitRes_;
  QSpinBox* res_[3];
  QComboBox* insert_;
  QPushButton* build_;
  QProgressBar* progress_;
  QLabel* info_;
  QGroupBox* grid_;
  QGroupBox* kd_;
  QDoubleSpinBox* ti_;
  QDoubleSpinBox* tt_;
  QDoubleSpinBox* emptyBonus_;
  QComboBox* builder_;
  QSpinBox* maxDepth_;
  QSpinBox* leafSize_;
  QCheckBox* mailboxes_;
  QGroupBox* bvh_;
  QComboBox* bvhBuilder_;
  QDoubleSpinBox* bvhTi_;
  QDoubleSpinBox* bvhTt_;
  QSpinBox* bvhBins_;
  QSpinBox* bvhLeafSize_;
  QSpinBox* bvhMaxDepth_;
  QComboBox* bvhOrder_;
  QGroupBox* octree_;
  QSpinBox* octreeLeaf_;
  QSpinBox* octreeMaxDepth_;
  QGroupBox* bsp_;
  QComboBox* bspDirections_;
  QSpinBox* bspCandidates_;
  QTimer* costsTimer_;
  bool settingUp_ = false;
  bool compact_ = false;
  QToolButton* options_;
  void showSection();  // setStructure: values set by the program, not edited
};

}  // namespace raystep::viz
