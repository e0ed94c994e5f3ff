#include "structure_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
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
  auto* top = new QHBoxLayout;
  top->addWidget(new QLabel(tr("<b>Structure</b>")));
  accel_ = new QComboBox;
  accel_->addItem(tr("uniform grid"), "grid");
  top->addWidget(accel_, 1);
  layout->addLayout(top);

  auto* grid = new QGroupBox(tr("Uniform grid"));
  auto* form = new QFormLayout(grid);
  density_ = new QDoubleSpinBox;
  density_->setObjectName("gridDensity");
  density_->setRange(0.1, 64.0);
  density_->setSingleStep(0.5);
  density_->setValue(3.0);
  density_->setToolTip(tr("d in max(nx, ny, nz) = d * cbrt(n)"));
  form->addRow(tr("density d"), density_);
  explicitRes_ = new QCheckBox(tr("explicit resolution"));
  auto* resRow = new QHBoxLayout;
  for (auto*& s : res_) {
    s = new QSpinBox;
    s->setRange(1, 4096);
    s->setValue(8);
    s->setEnabled(false);
    resRow->addWidget(s);
  }
  form->addRow(explicitRes_, resRow);
  insert_ = new QComboBox;
  insert_->addItem(tr("exact (triangle-box overlap)"), "exact");
  insert_->addItem(tr("bounding box"), "bbox");
  form->addRow(tr("insertion"), insert_);
  layout->addWidget(grid);
  connect(explicitRes_, &QCheckBox::toggled, this, [this](bool on) {
    for (auto* s : res_) s->setEnabled(on);
    density_->setEnabled(!on);
  });

  // The kd-tree's parameters, wired when the kd-tree core is merged.
  kd_ = new QGroupBox(tr("kd-tree (coming with the kd-tree core)"));
  auto* kdForm = new QFormLayout(kd_);
  auto spin = [](double v) {
    auto* s = new QDoubleSpinBox;
    s->setValue(v);
    return s;
  };
  kdForm->addRow(tr("t_i (intersection cost)"), spin(1.0));
  kdForm->addRow(tr("t_t (traversal cost)"), spin(1.0));
  kdForm->addRow(tr("empty bonus"), spin(0.2));
  auto* builder = new QComboBox;
  builder->addItems({tr("SAH"), tr("median")});
  kdForm->addRow(tr("builder"), builder);
  auto* depth = new QSpinBox;
  depth->setRange(1, 64);
  depth->setValue(24);
  kdForm->addRow(tr("max depth"), depth);
  kd_->setEnabled(false);
  layout->addWidget(kd_);

  auto* buildRow = new QHBoxLayout;
  build_ = new QPushButton(tr("Build"));
  build_->setObjectName("buildButton");
  progress_ = new QProgressBar;
  progress_->setRange(0, 1);
  progress_->setValue(0);
  progress_->setTextVisible(false);
  progress_->setMaximumHeight(12);
  buildRow->addWidget(build_);
  buildRow->addWidget(progress_, 1);
  layout->addLayout(buildRow);
  info_ = new QLabel;
  info_->setObjectName("structureInfo");
  info_->setWordWrap(true);
  layout->addWidget(info_);
  layout->addStretch();
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

void StructurePanel::setBusy(bool busy, const QString& what) {
  progress_->setRange(0, busy ? 0 : 1);  // 0..0: Qt's busy indicator
  progress_->setValue(busy ? 0 : 1);
  build_->setEnabled(!busy);
  if (busy) info_->setText(what);
}

void StructurePanel::setInfo(const QString& text) { info_->setText(text); }

}  // namespace raystep::viz
