#include "views/structure_panel.h"

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
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>

#include <algorithm>

#include "raystep/accel/bvh_names.h"

namespace raystep::viz {

StructurePanel::StructurePanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(3);
  auto* top = new QHBoxLayout;
  top->addWidget(new QLabel(tr("<b>Structure</b>")));
  accel_ = new QComboBox;
  accel_->setObjectName("accelBox");
  accel_->addItem(tr("uniform grid"), "grid");
  accel_->addItem(tr("kd-tree"), "kd");
  accel_->addItem(tr("bounding volume hierarchy"), "bvh");
  accel_->addItem(tr("octree"), "octree");
  accel_->addItem(tr("general BSP tree"), "bsp");
  top->addWidget(accel_, 1);
  build_ = new QPushButton(tr("Build"));
  build_->setObjectName("buildButton");
  top->addWidget(build_);
  options_ = new QToolButton;
  options_->setText(tr("Options"));
  options_->setCheckable(true);
  options_->setObjectName("structureOptions");
  options_->setToolTip(tr("Show the build options (at presenter scales the panel shows only its info line)"));
  options_->hide();
  top->addWidget(options_);
  layout->addLayout(top);

  auto* grid = grid_ = new QGroupBox(tr("Uniform grid"));
  auto* g = new QGridLayout(grid);
  g->setContentsMargins(6, 2, 6, 4);
  g->setVerticalSpacing(2);
  density_ = new QDoubleSpinBox;
  density_->setObjectName("gridDensity");
  density_->setRange(0.1, 64.0);
  density_->setSingleStep(0.5);
  density_->setValue(3.0);
  density_->setToolTip(
      tr("d in max(nx, ny, nz) = d * cbrt(n); coarsened (the info below says so) when the scene "
         "would need more than the reference budget, max(2^22, 32 n) references"));
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
  explicitRes_->setToolTip(
      tr("An explicit nx, ny, nz instead of the density rule; refused, not coarsened, past "
         "the reference budget"));
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

  // The kd-tree's parameters (defaults as KdOptions and the command line's).
  kd_ = new QGroupBox(tr("kd-tree"));
  auto* k = new QGridLayout(kd_);
  k->setContentsMargins(6, 2, 6, 4);
  k->setVerticalSpacing(2);
  KdOptions def;
  auto spin = [](const char* name, double lo, double hi, double step, int decimals, double v) {
    auto* s = new QDoubleSpinBox;
    s->setObjectName(name);
    s->setRange(lo, hi);
    s->setSingleStep(step);
    s->setDecimals(decimals);
    s->setValue(v);
    s->setMaximumWidth(80);
    return s;
  };
  ti_ = spin("kdTi", 0.01, 10000.0, 1.0, 2, def.t_i);
  ti_->setToolTip(tr("t_i: the cost of one ray-primitive test (lecture: t_i = 80 t_t)"));
  tt_ = spin("kdTt", 0.0, 10000.0, 0.5, 2, def.t_t);  // 0: free traversal steps, as core allows
  tt_->setToolTip(tr("t_t: the cost of one traversal step"));
  emptyBonus_ = spin("kdEmptyBonus", 0.0, 0.99, 0.05, 2, def.empty_bonus);
  emptyBonus_->setToolTip(tr("b in [0, 1): a split with an empty child costs t_t + (1 - b) t_i (...)"));
  k->addWidget(new QLabel(tr("t_i")), 0, 0);
  k->addWidget(ti_, 0, 1);
  k->addWidget(new QLabel(tr("t_t")), 0, 2);
  k->addWidget(tt_, 0, 3);
  k->addWidget(new QLabel(tr("empty bonus")), 0, 4);
  k->addWidget(emptyBonus_, 0, 5);
  builder_ = new QComboBox;
  builder_->setObjectName("kdBuilder");
  builder_->addItem(tr("SAH"), "kd");
  builder_->addItem(tr("median"), "kd-median");
  builder_->setToolTip(tr("SAH: the cheapest plane by the Surface Area Heuristic; median: the longest axis's middle"));
  k->addWidget(new QLabel(tr("builder")), 1, 0);
  k->addWidget(builder_, 1, 1);
  maxDepth_ = new QSpinBox;
  maxDepth_->setObjectName("kdMaxDepth");
  maxDepth_->setRange(0, kKdMaxDepth);
  maxDepth_->setValue(def.max_depth);
  maxDepth_->setSpecialValueText(tr("auto"));
  maxDepth_->setToolTip(
      tr("The depth limit; auto: max(8, 1.2 log2 N), with an empty bonus 8 + 1.3 log2 N (pbrt)"));
  k->addWidget(new QLabel(tr("max depth")), 1, 2);
  k->addWidget(maxDepth_, 1, 3);
  leafSize_ = new QSpinBox;
  leafSize_->setObjectName("kdLeafSize");
  leafSize_->setRange(1, 1000000);
  leafSize_->setValue(def.leaf_size);
  leafSize_->setToolTip(tr("A node with at most this many primitives is a leaf without a search"));
  k->addWidget(new QLabel(tr("leaf size")), 1, 4);
  k->addWidget(leafSize_, 1, 5);
  mailboxes_ = new QCheckBox(tr("mailboxes"));
  mailboxes_->setObjectName("kdMailboxes");
  mailboxes_->setChecked(true);
  mailboxes_->setToolTip(tr("Skip a primitive that an earlier leaf of the same ray already tested"));
  k->addWidget(mailboxes_, 2, 0, 1, 3);
  layout->addWidget(kd_);

  // The BVH's parameters (defaults as BvhOptions and the command line's).
  bvh_ = new QGroupBox(tr("Bounding volume hierarchy"));
  auto* b = new QGridLayout(bvh_);
  b->setContentsMargins(6, 2, 6, 4);
  b->setVerticalSpacing(2);
  BvhOptions bdef;
  bvhBuilder_ = new QComboBox;
  bvhBuilder_->setObjectName("bvhBuilder");
  bvhBuilder_->addItem(tr("binned SAH"), "bvh");
  bvhBuilder_->addItem(tr("full sweep SAH"), "bvh-sweep");
  bvhBuilder_->addItem(tr("object median"), "bvh-median");
  bvhBuilder_->addItem(tr("spatial splits (SBVH)"), "bvh-sbvh");
  bvhBuilder_->addItem(tr("4-wide (SIMD)"), "bvh4");
  bvhBuilder_->addItem(tr("8-wide (SIMD)"), "bvh8");
  bvhBuilder_->addItem(tr("4-wide SBVH"), "bvh4-sbvh");
  bvhBuilder_->addItem(tr("8-wide SBVH"), "bvh8-sbvh");
  bvhBuilder_->setToolTip(tr(
      "binned SAH: centroids in equal bins per axis (Wald 2007); full sweep: every centroid (the reference); "
      "object median: the longest axis's median centroid; spatial splits: also planes that cut primitives "
      "in two where the object split's boxes overlap (Stich et al. 2009); 4- and 8-wide: the binned tree or "
      "the SBVH collapsed into wide nodes tested with SIMD (the fast ones)"));
  b->addWidget(new QLabel(tr("builder")), 0, 0);
  b->addWidget(bvhBuilder_, 0, 1, 1, 3);
  bvhOrder_ = new QComboBox;
  bvhOrder_->setObjectName("bvhOrder");
  bvhOrder_->addItem(tr("entry distance"), "entry_distance");
  bvhOrder_->addItem(tr("split axis"), "split_axis");
  bvhOrder_->setToolTip(
      tr("Which child is walked first (the nearer): the smaller t_near, or by the sign of the "
         "ray's direction on the node's split axis (binary BVH)"));
  b->addWidget(new QLabel(tr("order")), 0, 4);
  b->addWidget(bvhOrder_, 0, 5);
  bvhTi_ = spin("bvhTi", 0.01, 10000.0, 1.0, 2, bdef.t_i);
  bvhTi_->setToolTip(tr("t_i: the cost of one ray-primitive test (lecture: t_i = 80 t_t)"));
  bvhTt_ = spin("bvhTt", 0.0, 10000.0, 0.5, 2, bdef.t_t);
  bvhTt_->setToolTip(tr("t_t: the cost of one traversal step"));
  b->addWidget(new QLabel(tr("t_i")), 1, 0);
  b->addWidget(bvhTi_, 1, 1);
  b->addWidget(new QLabel(tr("t_t")), 1, 2);
  b->addWidget(bvhTt_, 1, 3);
  bvhBins_ = new QSpinBox;
  bvhBins_->setObjectName("bvhBins");
  bvhBins_->setRange(2, 256);
  bvhBins_->setValue(bdef.bins);
  bvhBins_->setToolTip(tr("Binned SAH: bins per axis (Wald: 16 to 32)"));
  b->addWidget(new QLabel(tr("bins")), 1, 4);
  b->addWidget(bvhBins_, 1, 5);
  bvhLeafSize_ = new QSpinBox;
  bvhLeafSize_->setObjectName("bvhLeafSize");
  bvhLeafSize_->setRange(1, 1000000);
  bvhLeafSize_->setValue(bdef.leaf_size);
  bvhLeafSize_->setToolTip(tr("A node with at most this many primitives is a leaf without a search"));
  b->addWidget(new QLabel(tr("leaf size")), 2, 0);
  b->addWidget(bvhLeafSize_, 2, 1);
  bvhMaxDepth_ = new QSpinBox;
  bvhMaxDepth_->setObjectName("bvhMaxDepth");
  bvhMaxDepth_->setRange(1, kBvhMaxDepth);
  bvhMaxDepth_->setValue(bdef.max_depth);
  bvhMaxDepth_->setToolTip(tr("The depth limit"));
  b->addWidget(new QLabel(tr("max depth")), 2, 2);
  b->addWidget(bvhMaxDepth_, 2, 3);
  layout->addWidget(bvh_);

  // The octree's parameters (defaults as OctreeOptions and the command line's).
  octree_ = new QGroupBox(tr("Octree"));
  auto* oc = new QGridLayout(octree_);
  oc->setContentsMargins(6, 2, 6, 4);
  oc->setVerticalSpacing(2);
  OctreeOptions odef;
  octreeLeaf_ = new QSpinBox;
  octreeLeaf_->setObjectName("octreeLeaf");
  octreeLeaf_->setRange(1, 1 << 24);
  octreeLeaf_->setValue(odef.leaf_size);
  octreeLeaf_->setToolTip(
      tr("K: a cell with at most K primitives is a leaf; a fuller one is split at its "
         "centre into eight"));
  oc->addWidget(new QLabel(tr("leaf size K")), 0, 0);
  oc->addWidget(octreeLeaf_, 0, 1);
  octreeMaxDepth_ = new QSpinBox;
  octreeMaxDepth_->setObjectName("octreeMaxDepth");
  octreeMaxDepth_->setRange(0, kOctreeMaxDepth);
  octreeMaxDepth_->setValue(odef.max_depth);
  octreeMaxDepth_->setSpecialValueText(tr("auto"));
  octreeMaxDepth_->setToolTip(tr("The depth limit; auto: clamp(ceil(log2 N / 2) + 6, 8, 20)"));
  oc->addWidget(new QLabel(tr("max depth")), 0, 2);
  oc->addWidget(octreeMaxDepth_, 0, 3);
  layout->addWidget(octree_);

  // The general BSP tree's own parameters; its costs, depth limit, leaf size and mailboxes are the kd-tree's
  // (the kd-tree's box is shown with it, as raystep's --ti, --tt, --max-depth, --leaf-size, --mailbox).
  bsp_ = new QGroupBox(tr("General BSP tree (planes of any orientation)"));
  auto* bs = new QGridLayout(bsp_);
  bs->setContentsMargins(6, 2, 6, 4);
  bs->setVerticalSpacing(2);
  BspOptions bspdef;
  bspDirections_ = new QComboBox;
  bspDirections_->setObjectName("bspDirections");
  bspDirections_->addItem(tr("both"), "both");
  bspDirections_->addItem(tr("k-DOP directions"), "kdop");
  bspDirections_->addItem(tr("autopartition"), "autopartition");
  bspDirections_->setCurrentIndex(bspDirections_->findData(bsp_directions_name(bspdef.directions)));
  bspDirections_->setToolTip(
      tr("The candidate planes' normals: the 13 k-DOP directions (3 axes, 6 face and 4 body diagonals), "
         "the primitives' own planes (autopartition), or both"));
  bs->addWidget(new QLabel(tr("directions")), 0, 0);
  bs->addWidget(bspDirections_, 0, 1);
  bspCandidates_ = new QSpinBox;
  bspCandidates_->setObjectName("bspCandidates");
  bspCandidates_->setRange(1, 4096);
  bspCandidates_->setValue(bspdef.candidates);
  bspCandidates_->setToolTip(
      tr("Candidate positions per direction and node (primitive planes: as many "
         "with autopartition alone, a quarter with both)"));
  bs->addWidget(new QLabel(tr("candidates")), 0, 2);
  bs->addWidget(bspCandidates_, 0, 3);
  layout->addWidget(bsp_);
  connect(bvhBuilder_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this] {
    const QString k = bvhBuilder_->currentData().toString();
    const std::optional<BvhName> name = parse_bvh_name(k.toStdString());
    bvhBins_->setEnabled(name && (name->builder == BvhBuilder::binned || name->builder == BvhBuilder::sbvh));
    bvhOrder_->setEnabled(!is_wide_bvh_name(k.toStdString()));  // the wide walk orders by entry distance
  });
  connect(accel_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &StructurePanel::showSection);
  connect(options_, &QToolButton::toggled, this, &StructurePanel::showSection);
  showSection();

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
  // An edited cost rebuilds once the spin box rests (not once per arrow click while it is held).
  costsTimer_ = new QTimer(this);
  costsTimer_->setSingleShot(true);
  costsTimer_->setInterval(400);
  connect(costsTimer_, &QTimer::timeout, this, &StructurePanel::kdCostsEdited);
  for (QDoubleSpinBox* s : {ti_, tt_, emptyBonus_})
    connect(s, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this] {
      if (!settingUp_) costsTimer_->start();
    });
}

std::string StructurePanel::accelName() const {
  const QString a = accel_->currentData().toString();
  if (a == "grid") return "grid";
  if (a == "bvh") return bvhBuilder_->currentData().toString().toStdString();
  if (a == "octree" || a == "bsp") return a.toStdString();
  return builder_->currentData().toString().toStdString();
}

void StructurePanel::showSection() {
  const QString a = accel_->currentData().toString();
  const bool shown = !compact_ || options_->isChecked();
  grid_->setVisible(shown && a == "grid");
  kd_->setVisible(shown && (a == "kd" || a == "bsp"));
  bvh_->setVisible(shown && a == "bvh");
  octree_->setVisible(shown && a == "octree");
  bsp_->setVisible(shown && a == "bsp");
  // The BSP tree takes the kd-tree's costs, depth limit, leaf size and mailboxes, not its builder or bonus.
  kd_->setTitle(a == "bsp" ? tr("Costs and limits (the kd-tree's)") : tr("kd-tree"));
  builder_->setEnabled(a != "bsp");
  emptyBonus_->setEnabled(a != "bsp");
}

void StructurePanel::setCompact(bool on) {
  compact_ = on;
  options_->setVisible(on);
  options_->setChecked(false);
  showSection();
}

StructureOptions StructurePanel::options() const {
  StructureOptions so;
  GridOptions& o = so.grid;
  o.density = float(density_->value());
  if (explicitRes_->isChecked()) o.resolution = std::array<int, 3>{res_[0]->value(), res_[1]->value(), res_[2]->value()};
  o.exact_insert = insert_->currentData().toString() == "exact";
  so.kd.builder = builder_->currentData().toString() == "kd-median" ? KdBuilder::median : KdBuilder::sah;
  so.kd.t_i = float(ti_->value());
  so.kd.t_t = float(tt_->value());
  so.kd.empty_bonus = float(emptyBonus_->value());
  so.kd.max_depth = maxDepth_->value();
  so.kd.leaf_size = leafSize_->value();
  so.kd_mailboxes = mailboxes_->isChecked();
  const QString bb = bvhBuilder_->currentData().toString();
  so.bvh.builder = bb == "bvh-sweep"    ? BvhBuilder::sweep
                   : bb == "bvh-median" ? BvhBuilder::median
                                        : BvhBuilder::binned;
  so.bvh.t_i = float(bvhTi_->value());
  so.bvh.t_t = float(bvhTt_->value());
  so.bvh.bins = bvhBins_->value();
  so.bvh.leaf_size = bvhLeafSize_->value();
  so.bvh.max_depth = bvhMaxDepth_->value();
  so.bvh_order =
      bvhOrder_->currentData().toString() == "split_axis" ? BvhOrder::split_axis : BvhOrder::entry_distance;
  so.octree.leaf_size = octreeLeaf_->value();
  so.octree.max_depth = octreeMaxDepth_->value();
  parse_bsp_directions(bspDirections_->currentData().toString().toStdString(), &so.bsp.directions);
  so.bsp.candidates = bspCandidates_->value();
  so.bsp.t_i = so.kd.t_i;
  so.bsp.t_t = so.kd.t_t;
  so.bsp.max_depth = so.kd.max_depth;
  so.bsp.leaf_size = so.kd.leaf_size;
  return so;
}

void StructurePanel::setStructure(const std::string& accelName, const StructureOptions& so) {
  settingUp_ = true;
  const bool bvh = accelName.rfind("bvh", 0) == 0;
  const int own = accel_->findData(QString::fromStdString(accelName));  // grid, octree, bsp
  accel_->setCurrentIndex(own >= 0 ? own : bvh ? 2 : 1);
  octreeLeaf_->setValue(so.octree.leaf_size);
  octreeMaxDepth_->setValue(so.octree.max_depth);
  bspDirections_->setCurrentIndex(
      std::max(0, bspDirections_->findData(bsp_directions_name(so.bsp.directions))));
  bspCandidates_->setValue(so.bsp.candidates);
  if (bvh) {
    const int i = bvhBuilder_->findData(QString::fromStdString(accelName));
    bvhBuilder_->setCurrentIndex(i >= 0 ? i : 0);
  }
  bvhTi_->setValue(so.bvh.t_i);
  bvhTt_->setValue(so.bvh.t_t);
  bvhBins_->setValue(so.bvh.bins);
  bvhLeafSize_->setValue(so.bvh.leaf_size);
  bvhMaxDepth_->setValue(so.bvh.max_depth);
  bvhOrder_->setCurrentIndex(so.bvh_order == BvhOrder::split_axis ? 1 : 0);
  builder_->setCurrentIndex(accelName == "kd-median" ? 1 : 0);
  // The BSP tree's costs and limits are shown in the kd-tree's boxes.
  const bool bsp = accelName == "bsp";
  ti_->setValue(bsp ? so.bsp.t_i : so.kd.t_i);
  tt_->setValue(bsp ? so.bsp.t_t : so.kd.t_t);
  emptyBonus_->setValue(so.kd.empty_bonus);
  maxDepth_->setValue(bsp ? so.bsp.max_depth : so.kd.max_depth);
  leafSize_->setValue(bsp ? so.bsp.leaf_size : so.kd.leaf_size);
  mailboxes_->setChecked(so.kd_mailboxes);
  const GridOptions& o = so.grid;
  density_->setValue(o.density);
  explicitRes_->setChecked(bool(o.resolution));
  if (o.resolution)
    for (int a = 0; a < 3; ++a) res_[a]->setValue((*o.resolution)[size_t(a)]);
  insert_->setCurrentIndex(o.exact_insert ? 0 : 1);
  settingUp_ = false;
}

void StructurePanel::setBusy(bool busy) {
  progress_->setRange(0, busy ? 0 : 1);  // 0..0: Qt's busy indicator
  progress_->setValue(0);  // idle: empty
}

void StructurePanel::setInfo(const QString& text) { info_->setText(text); }

QString StructurePanel::info() const { return info_->text(); }

bool StructurePanel::costsEditPending() const { return costsTimer_->isActive(); }

}  // namespace raystep::viz
