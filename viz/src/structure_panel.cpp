#include "structure_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

namespace raystep::viz {

StructurePanel::StructurePanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(3);
  auto* top = new QHBoxLayout;
  top->addWidget(new QLabel(tr("<b>Structure</b>")));
  accel_ = new QComboBox;
  accel_->addItem(tr("uniform grid"), "grid");
  top->addWidget(accel_, 1);
  build_ = new QPushButton(tr("Build"));
  build_->setObjectName("buildButton");
  top->addWidget(build_);
  layout->addLayout(top);

  auto* grid = new QGroupBox(tr("Uniform grid"));
  auto* g = new QGridLayout(grid);
  g->setContentsMargins(6, 2, 6, 4);
  g->setVerticalSpacing(2);
  density_ = new QDoubleSpinBox;
  density_->setObjectName("gridDensity");
  density_->setRange(0.1, 64.0);
  density_->setSingleStep(0.5);
  density_->setValue(3.0);
  density_->setToolTip(tr("d in max(nx, ny, nz) = d * cbrt(n)"));
  g->addWidget(new QLabel(tr("density d")), 0, 0);
  g->addWidget(density_, 0, 1);
  insert_ = new QComboBox;
  insert_->addItem(tr("exact"), "exact");
  insert_->addItem(tr("bounding box"), "bbox");
  insert_->setToolTip(tr("exact: a primitive goes in the cells it overlaps (triangle-box test); "
                         "bounding box: in every cell its bounding box overlaps"));
  g->addWidget(new QLabel(tr("insertion")), 0, 2);
  g->addWidget(insert_, 0, 3);
  explicitRes_ = new QCheckBox(tr("resolution"));
  explicitRes_->setToolTip(tr("An explicit nx, ny, nz instead of the density rule"));
  g->addWidget(explicitRes_, 1, 0);
  auto* resRow = new QHBoxLayout;
  for (auto*& r : res_) {
    r = new QSpinBox;
    r->setRange(1, 4096);
    r->setValue(8);
    r->setEnabled(false);
    resRow->addWidget(r);
  }
  g->addLayout(resRow, 1, 1, 1, 3);
  layout->addWidget(grid);
  connect(explicitRes_, &QCheckBox::toggled, this, [this](bool on) {
    for (auto* r : res_) r->setEnabled(on);
    density_->setEnabled(!on);
  });

  // The kd-tree's parameters, wired when the kd-tree core is merged.
  kd_ = new QGroupBox(tr("kd-tree (with the kd-tree core)"));
  auto* k = new QGridLayout(kd_);
  k->setContentsMargins(6, 2, 6, 4);
  k->setVerticalSpacing(2);
  auto spin = [](double v) {
    auto* s = new QDoubleSpinBox;
    s->setValue(v);
    s->setMaximumWidth(70);
    return s;
  };
  k->addWidget(new QLabel(tr("t_i")), 0, 0);
  k->addWidget(spin(1.0), 0, 1);
  k->addWidget(new QLabel(tr("t_t")), 0, 2);
  k->addWidget(spin(1.0), 0, 3);
  k->addWidget(new QLabel(tr("empty bonus")), 0, 4);
  k->addWidget(spin(0.2), 0, 5);
  auto* builder = new QComboBox;
  builder->addItems({tr("SAH"), tr("median")});
  k->addWidget(new QLabel(tr("builder")), 1, 0);
  k->addWidget(builder, 1, 1, 1, 2);
  auto* depth = new QSpinBox;
  depth->setRange(1, 64);
  depth->setValue(24);
  k->addWidget(new QLabel(tr("max depth")), 1, 3, 1, 2);
  k->addWidget(depth, 1, 5);
  kd_->setEnabled(false);
  layout->addWidget(kd_);

  progress_ = new QProgressBar;
  progress_->setRange(0, 1);
  progress_->setValue(0);
  progress_->setTextVisible(false);
  progress_->setMaximumHeight(8);
  layout->addWidget(progress_);
  info_ = new QLabel;
  info_->setObjectName("structureInfo");
  info_->setWordWrap(true);
  layout->addWidget(info_);
  connect(build_, &QPushButton::clicked, this, &StructurePanel::buildRequested);
}

GridOptions StructurePanel::gridOptions() const {
  GridOptions o;
  o.density = float(density_->value());
  if (explicitRes_->isChecked()) o.resolution = std::array<int, 3>{res_[0]->value(), res_[1]->value(), res_[2]->value()};
  o.exact_insert = insert_->currentData().toString() == "exact";
  return o;
}

void StructurePanel::setGridOptions(const GridOptions& o) {
  density_->setValue(o.density);
  explicitRes_->setChecked(bool(o.resolution));
  if (o.resolution)
    for (int a = 0; a < 3; ++a) res_[a]->setValue((*o.resolution)[size_t(a)]);
  insert_->setCurrentIndex(o.exact_insert ? 0 : 1);
}

void StructurePanel::setBusy(bool busy) {
  progress_->setRange(0, busy ? 0 : 1);  // 0..0: Qt's busy indicator
  progress_->setValue(0);  // idle: empty
}

void StructurePanel::setInfo(const QString& text) { info_->setText(text); }

}  // namespace raystep::viz
