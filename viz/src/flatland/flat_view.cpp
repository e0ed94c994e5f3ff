#include "flatland/flat_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <QCheckBox>
#include <QJsonArray>
#include <QMouseEvent>
#include <QPainter>

#include "app/session.h"
#include "lesson/tree_diagram.h"
#include "views/kd_tree_model.h"
#include "raystep/util/error.h"

namespace raystep::viz {

namespace {

// Points to pixels at the desk (a figure's 1 pt line is 1.4 pixels wide) and the caption's type.
constexpr double kPixelsPerPoint = 1.4;
constexpr int kCaptionPixels = 19, kHintPixels = 13;
const QColor kSelected(0, 158, 115);  // the tree view's and the 3D view's selected node: teal

bool contains(const std::vector<glm::vec2>& polygon, glm::vec2 p) {  // a convex, counter-clockwise polygon
  if (polygon.size() < 3) return false;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const glm::vec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    if ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) < 0.f) return false;
  }
  return true;
}

}  // namespace

FlatView::FlatView(Session* session, QWidget* parent) : QWidget(parent), session_(session) {
  setMinimumSize(320, 240);
  setMouseTracking(true);
  buildBox_ = new QCheckBox(tr("Build so far"), this);
  buildBox_->setObjectName("flatBuildSoFar");
  buildBox_->setToolTip(tr("Only the splits of the nodes made up to the selected one (right-click a cell, or pick "
                           "a node in the tree view): step through the build split by split"));
  linesBox_ = new QCheckBox(tr("Crofton lines"), this);
  linesBox_->setObjectName("flatCroftonLines");
  linesBox_->setToolTip(tr("Random lines at the selected node: the share meeting each child against its "
                           "perimeter ratio, the SAH's probability in the plane"));
  aaBox_ = new QCheckBox(tr("Anti-aliasing"), this);
  aaBox_->setObjectName("flatAntiAliasing");
  aaBox_->setToolTip(tr("The picture's pixels over the scene: each pixel sampled with the picture's "
                        "anti-aliasing (its samples drawn), its exact coverage, and the error"));
  connect(session_, &Session::pictureChanged, this, [this] {  // another size or anti-aliasing
    if (!aaBox_->isChecked()) return;
    sampleAa();
    walkChanged();
  });
  connect(aaBox_, &QCheckBox::toggled, this, [this] {
    sampleAa();
    walkChanged();
  });
  connect(buildBox_, &QCheckBox::toggled, this, [this] {
    makeStill();
    walkChanged();
  });
  connect(linesBox_, &QCheckBox::toggled, this, [this] {
    throwLines();
    walkChanged();
  });
  setAttribute(Qt::WA_OpaquePaintEvent);
  connect(session_, &Session::sceneChanged, this, &FlatView::structureChanged);
  connect(session_, &Session::structureChanged, this, &FlatView::structureChanged);
  // A new trace or ray always comes with a stepChanged: the walk is drawn once.
  connect(session_, &Session::stepChanged, this, &FlatView::walkChanged);
  connect(session_, &Session::selectedNodeChanged, this, [this] {
    if (buildBox_->isChecked()) makeStill();
    throwLines();
    walkChanged();
  });
  treeTimer_.setSingleShot(true);
  treeTimer_.setInterval(40);
  connect(&treeTimer_, &QTimer::timeout, this, [this] {
    drawTree();
    layout();
    update();
  });
}

FlatView::~FlatView() = default;

void FlatView::setScale(double scale) {
  scale_ = scale;
  walkChanged();  // the tree's picture and the layout follow the type
}

void FlatView::structureChanged() {
  problem_.clear();
  structure_ = session_->structureShared();
  hasOutline_ = false;
  tree_.reset();
  const SceneData* scene = session_->scene();
  if (!scene || !scene->scene.flat) {
    still_ = Figure{};
    under_ = QPixmap();
    problem_ = tr("A 3D scene: the 2D view draws a scene with \"dimensions\": 2 (scenes/flatland).");
    walkChanged();
    return;
  }
  const Flatland& flat = *scene->scene.flat;
  if (structure_ && structure_->scene.get() == scene && structure_->accel) {
    try {
      outline_ = plane_outline(*structure_->accel);
      hasOutline_ = true;
    } catch (const InputError& e) {
      problem_ = QString::fromStdString(e.what());
    }
    tree_ = treeShapeOf(*structure_);
  }
  if (!session_->trace()) {
    origin_ = flat.ray_origin;
    direction_ = flat.ray_direction;
  }
  makeStill();
  throwLines();
  sampleAa();
  walkChanged();
}

void FlatView::sampleAa() {
  aa_.reset();
  aaProblem_.clear();
  const SceneData* scene = session_->scene();
  if (!aaBox_->isChecked() || !scene || !scene->scene.flat || !structure_ || !structure_->accel) return;
  try {
    FlatAaInput in;
    in.scene = &scene->scene;
    in.accel = structure_->accel.get();
    in.aa = antiAliasingOf(scene->scene, aaSpec_.toStdString());
    in.width = session_->imageWidth();
    in.height = session_->imageHeight();
    in.column = aaColumn_;
    aa_ = std::make_unique<FlatAa>(flat_aa_figure(in));
  } catch (const InputError& e) {
    aaProblem_ = QString::fromStdString(e.what());
  }
}

void FlatView::setAntiAliasingView(bool on) { aaBox_->setChecked(on); }
bool FlatView::antiAliasingView() const { return aaBox_->isChecked(); }
void FlatView::setAntiAliasing(const QString& spec) {
  if (spec == aaSpec_) return;
  aaSpec_ = spec;
  if (aaBox_->isChecked()) {
    sampleAa();
    walkChanged();
  }
}

void FlatView::makeStill() {
  const SceneData* scene = session_->scene();
  if (!scene || !scene->scene.flat) return;
  // The frame holds the scene's own ray's origin, and stays put while the ray is dragged or the build stepped.
  const Flatland& flat = *scene->scene.flat;
  const glm::vec2 o = flat.ray_origin;
  const int built = buildBox_->isChecked() && tree_ ? std::max(0, session_->selectedNode()) : -1;
  still_ = flat_figure_still(scene->scene, hasOutline_ ? &outline_ : nullptr, flat.has_ray ? &o : nullptr, built);
  under_ = QPixmap();  // drawn again with the new still layers
}

void FlatView::throwLines() {
  crofton_ = LinesMeetingChildren{};
  croftonNode_ = -1;
  croftonCaption_.clear();
  const int n = session_->selectedNode();
  if (!linesBox_->isChecked() || !tree_ || n < 0 || size_t(n) >= tree_->size()) return;
  if (structure_ && structure_->bsp()) {
    croftonCaption_ = {tr("Crofton lines: the BSP tree's cells are polygons; here a kd-tree's, a quadtree's or a "
                          "BVH's boxes").toStdString()};
    return;
  }
  if (tree_->leaf(uint32_t(n))) {
    croftonCaption_ = {tr("Crofton lines: node %1 is a leaf; select an inner node").arg(n).toStdString()};
    return;
  }
  std::vector<Bounds3> children;
  for (int r = 0; r < tree_->children(uint32_t(n)); ++r) children.push_back(tree_->box(tree_->child(uint32_t(n), r)));
  const SplitSpace space = structure_ ? structure_->scene->scene.geometry.split_space() : SplitSpace{};
  crofton_ = lines_meeting_children(tree_->box(uint32_t(n)), children, 4000, 1, space, 120);
  croftonNode_ = n;
  std::string line = "Crofton at node " + std::to_string(n) + ": of " + std::to_string(crofton_.meeting_node) +
                     " random lines meeting it,";
  char part[128];
  for (size_t c = 0; c < children.size(); ++c) {
    const std::string side = tree_->side(tree_->child(uint32_t(n), int(c))).toStdString();
    std::snprintf(part, sizeof part, "%s %s %.1f%% (perimeter ratio %.1f%%)", c ? ";" : "", side.c_str(),
                  100.0 * crofton_.share[c], 100.0 * crofton_.ratio[c]);
    line += part;
  }
  croftonCaption_ = {line};
}

bool FlatView::rayInPlane() const {
  const TracedRay* r = session_->ray();
  return r && r->ray.direction.z == 0.f && r->ray.origin.z == 0.f &&
         (r->ray.direction.x != 0.f || r->ray.direction.y != 0.f);
}

void FlatView::walkChanged() {
  walk_ = FlatWalkLayers{};
  if (!tree_) treeImage_ = QImage();
  const SceneData* scene = session_->scene();
  if (scene && scene->scene.flat) {
    const TracedRay* r = session_->ray();
    if (rayInPlane()) {
      origin_ = glm::vec2(r->ray.origin);
      direction_ = glm::vec2(r->ray.direction);
    }
    // The walk is drawn from the session's trace when it is a walk through the structure shown: one ray.
    Trace one;
    const Trace* trace = nullptr;
    if (r && session_->trace()) {
      if (session_->trace()->rays.size() == 1) {
        trace = session_->trace();
      } else {  // the current ray of several (a pixel's samples): the figure walks the first ray of its trace
        one = *session_->trace();
        one.rays = {*r};
        trace = &one;
      }
    }
    FlatFigureInput in;
    in.scene = &scene->scene;
    in.outline = hasOutline_ ? &outline_ : nullptr;
    in.trace = trace;
    in.step = trace ? std::min(session_->step(), int(r->events.size()) - 1) : -1;
    try {
      walk_ = flat_figure_walk(in, still_);
    } catch (const InputError& e) {
      walk_.caption = {e.what()};
    }
    if (r && !rayInPlane())
      walk_.caption.push_back(tr("A pixel's ray looks down on the plane: drag in the picture for a ray in it")
                                  .toStdString());
    walk_.caption.insert(walk_.caption.end(), croftonCaption_.begin(), croftonCaption_.end());
    if (aaBox_->isChecked())  // the pixels instead of the walk: their caption
      walk_.caption = aa_ ? aa_->figure.caption : std::vector<std::string>{aaProblem_.toStdString()};
    // While a hand drags the ray the tree follows a moment later (a big tree takes longer to draw than a
    // frame lasts); the picture follows at once.
    if (drag_ == Drag::none)
      drawTree();
    else
      treeTimer_.start();
  }
  layout();
  update();
}

void FlatView::drawTree() {
  treeTimer_.stop();
  treeImage_ = QImage();
  if (!tree_) return;
  TreeMarks marks;
  marks.selected = session_->selectedNode();
  if (const TracedRay* r = session_->ray()) {
    const replay::ReplayState& st = session_->state();
    if (st.node_event >= 0 && !st.ended) marks.current = r->events[size_t(st.node_event)].node;
    for (const replay::StackEntry& e : st.stack) marks.stack.push_back(e.node);
    marks.visited = st.visited_nodes;
  }
  treeImage_ = drawTreeDiagram(*tree_, marks, 31);
}

void FlatView::layout() {
  const double s = scale_;
  const QRectF all = QRectF(rect()).adjusted(8 * s, 6 * s, -8 * s, -6 * s);
  hintRect_ = QRectF(all.left(), all.top(), all.width(), kHintPixels * s * 1.6);
  // The two boxes at the top right, the hint beside them.
  const bool flat = session_->scene() && session_->scene()->scene.flat;
  const bool trees = bool(tree_) && !aaBox_->isChecked();
  buildBox_->setVisible(trees);
  linesBox_->setVisible(trees);
  aaBox_->setVisible(flat);
  int right = int(all.right());
  for (QCheckBox* box : {linesBox_, buildBox_, aaBox_}) {
    if (!box->isVisible()) continue;
    const QSize b = box->sizeHint();
    box->setGeometry(right - b.width(), int(all.top()), b.width(), b.height());
    right = box->x() - 8;
    hintRect_.setHeight(std::max(hintRect_.height(), double(b.height())));
  }
  hintRect_.setRight(right);
  // The caption's lines at the bottom, wrapped to the width: room for four lines at every step (the step's
  // event, the stack, a grid's tMax), more only where they wrap beyond it.
  QFont font = this->font();
  font.setPixelSize(int(kCaptionPixels * s));
  const QFontMetricsF fm(font);
  double captionHeight = 0;
  const double room = 4 * (fm.lineSpacing() + 4 * s);
  for (const std::string& line : walk_.caption)
    captionHeight += fm.boundingRect(QRectF(0, 0, all.width(), 1e6), Qt::TextWordWrap, QString::fromStdString(line))
                         .height() +
                     4 * s;
  captionHeight = std::max(captionHeight, room);
  captionRect_ = QRectF(all.left(), all.bottom() - captionHeight, all.width(), captionHeight);
  QRectF picture(all.left(), hintRect_.bottom(), all.width(), captionRect_.top() - hintRect_.bottom() - 4 * s);
  // A tree's room beside the picture (a wide view: two fifths of its width) or below it (a tall one: a
  // third of its height), the same at every step so that the picture stays put under a dragging hand; the
  // tree's drawing (its marked nodes change with the step) fits inside, never enlarged.
  treeRect_ = treeRoom_ = QRectF();
  if (tree_ && !aaBox_->isChecked() && picture.width() > 200 && picture.height() > 200) {
    if (picture.width() >= picture.height()) {
      treeRoom_ = QRectF(picture.right() - 0.4 * picture.width(), picture.top(), 0.4 * picture.width(),
                         picture.height());
      picture.setRight(treeRoom_.left() - 10 * s);
    } else {
      treeRoom_ = QRectF(picture.left(), picture.bottom() - picture.height() / 3, picture.width(),
                         picture.height() / 3);
      picture.setBottom(treeRoom_.top() - 6 * s);
    }
    if (!treeImage_.isNull()) {
      // At the desk its own size at most; before a room (presenter scale) up to twice that, for the back row.
      const double most = scale_ > 1.0 ? 2.0 : 1.0;
      const double k = std::min({most, treeRoom_.width() / treeImage_.width(), treeRoom_.height() / treeImage_.height()});
      const QSizeF size(treeImage_.width() * k, treeImage_.height() * k);
      treeRect_ = QRectF(treeRoom_.center().x() - size.width() / 2, treeRoom_.top(), size.width(), size.height());
    }
  }
  if (aaBox_->isChecked()) {  // the pixels' figure has a frame of its own: its panels in a row or a column
    const double r = session_->imageHeight() > 0 ? double(session_->imageWidth()) / session_->imageHeight() : 1.0;
    const double row = std::min(picture.width() / (3.2 * r), picture.height() / 1.2);
    const double column = std::min(picture.width() / r, picture.height() / 3.6);
    if ((column > row) != aaColumn_) {
      aaColumn_ = column > row;
      sampleAa();
    }
    aaFrame_ = aa_ ? FigureFrame::fit(aa_->figure, picture, kPixelsPerPoint * s) : FigureFrame{};
  }
  const FigureFrame before = frame_;
  frame_ = FigureFrame::fit(still_, picture, kPixelsPerPoint * s);
  if (frame_.target != before.target || frame_.pixelsPerPoint != before.pixelsPerPoint || under_.isNull())
    cacheStill();
}

void FlatView::cacheStill() {
  under_ = QPixmap(size());
  under_.fill(Qt::white);
  over_ = QPixmap(size());
  over_.fill(Qt::transparent);
  QPainter under(&under_), over(&over_);
  for (const FigureLayer& layer : still_.layers)
    paintFigureLayer(layer.name == "shapes" ? over : under, frame_, layer);
}

void FlatView::resizeEvent(QResizeEvent*) {
  under_ = QPixmap();
  layout();
}

void FlatView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  if (aaBox_->isChecked()) {
    p.fillRect(rect(), Qt::white);
    if (aa_)
      for (const FigureLayer& layer : aa_->figure.layers) paintFigureLayer(p, aaFrame_, layer);
    paintCaption(p);
    return;
  }
  if (under_.size() != size()) cacheStill();
  p.drawPixmap(0, 0, under_);
  p.setRenderHint(QPainter::Antialiasing);
  p.setClipRect(frame_.target.adjusted(-2, -2, 2, 2));
  paintFigureLayer(p, frame_, walk_.walk);
  // The selected node (the tree view's, the SAH inspector's): teal; Crofton's lines over it, faint.
  const int sel = session_->selectedNode();
  if (hasOutline_ && sel >= 0 && size_t(sel) < outline_.regions.size() && outline_.regions[size_t(sel)].node == sel) {
    QPolygonF poly;
    for (const glm::vec2& q : outline_.regions[size_t(sel)].polygon) poly << frame_.map(q);
    p.setPen(QPen(kSelected, 3.0 * scale_));
    QColor fill = kSelected;
    fill.setAlphaF(0.12);
    p.setBrush(fill);
    p.drawPolygon(poly);
  }
  if (croftonNode_ >= 0) {
    QColor c(120, 60, 160);
    c.setAlphaF(0.45);
    p.setPen(QPen(c, 1.0 * scale_));
    for (const auto& [a, b] : crofton_.kept) p.drawLine(frame_.map(glm::vec2(a)), frame_.map(glm::vec2(b)));
  }
  p.drawPixmap(0, 0, over_);
  paintFigureLayer(p, frame_, walk_.marks);
  paintFigureLayer(p, frame_, walk_.ray);
  // The origin's handle: a ring a hand can grab.
  const SceneData* scene = session_->scene();
  if (scene && scene->scene.flat && (rayInPlane() || !session_->trace())) {
    p.setPen(QPen(QColor(215, 25, 25), 2.0 * scale_));
    p.setBrush(Qt::NoBrush);
    p.drawEllipse(frame_.map(origin_), 9 * scale_, 9 * scale_);
    if (!session_->trace()) {  // no walk yet: the ray alone
      const glm::vec2 d = glm::length(direction_) > 0.f ? glm::normalize(direction_) : glm::vec2(1.f, 0.f);
      p.drawLine(frame_.map(origin_), frame_.map(origin_ + 2.f * (still_.hi.x - still_.lo.x) * d));
    }
  }
  p.setClipping(false);
  QFont font = this->font();
  font.setPixelSize(int(kHintPixels * scale_));
  p.setFont(font);
  p.setPen(QColor(90, 90, 90));
  const QString hint =
      problem_.isEmpty() ? tr("Drag the red ring: the ray's origin moves; drag elsewhere: the ray aims there.")
                         : problem_;
  p.drawText(hintRect_, Qt::AlignLeft | Qt::AlignVCenter,
             QFontMetricsF(font).elidedText(hint, Qt::ElideRight, hintRect_.width()));
  if (!treeRect_.isNull()) {
    p.setRenderHint(QPainter::SmoothPixmapTransform);
    p.drawImage(treeRect_, treeImage_);
  }
  paintCaption(p);
}

void FlatView::paintCaption(QPainter& p) {
  QFont font = this->font();
  font.setPixelSize(int(kCaptionPixels * scale_));
  p.setFont(font);
  p.setPen(QColor(25, 25, 30));
  double y = captionRect_.top();
  const QFontMetricsF fm(font);
  for (const std::string& line : walk_.caption) {
    const QString text = QString::fromStdString(line);
    const QRectF r = fm.boundingRect(QRectF(captionRect_.left(), y, captionRect_.width(), 1e6), Qt::TextWordWrap, text);
    p.drawText(QRectF(captionRect_.left(), y, captionRect_.width(), r.height()), Qt::TextWordWrap, text);
    y += r.height() + 4 * scale_;
  }
}

void FlatView::mousePressEvent(QMouseEvent* e) {
  if (aaBox_->isChecked()) return;  // the pixels' figure: nothing to drag
  if (e->button() == Qt::RightButton && frame_.target.contains(e->pos())) {
    const int n = nodeAt(frame_.unmap(e->pos()));
    if (n >= 0) Q_EMIT nodePicked(n);
    return;
  }
  const SceneData* scene = session_->scene();
  if (e->button() != Qt::LeftButton || !scene || !scene->scene.flat || !frame_.target.contains(e->pos())) return;
  const QPointF o = frame_.map(origin_);
  const double grab = 14 * scale_;
  drag_ = QLineF(o, e->pos()).length() <= grab ? Drag::origin : Drag::direction;
  setCursor(drag_ == Drag::origin ? Qt::ClosedHandCursor : Qt::CrossCursor);
  if (drag_ == Drag::direction) drag(e->pos());
}

void FlatView::mouseMoveEvent(QMouseEvent* e) {
  if (drag_ != Drag::none && (e->buttons() & Qt::LeftButton)) return drag(e->pos());
  // Over the handle: the hand says it can be grabbed.
  const bool over = session_->scene() && session_->scene()->scene.flat &&
                    QLineF(frame_.map(origin_), e->pos()).length() <= 14 * scale_;
  setCursor(over ? Qt::OpenHandCursor : Qt::ArrowCursor);
}

void FlatView::mouseReleaseEvent(QMouseEvent* e) {
  if (drag_ != Drag::none && e->button() == Qt::LeftButton) drag(e->pos());
  drag_ = Drag::none;
  unsetCursor();
  if (treeTimer_.isActive()) {  // let go: the tree at once
    drawTree();
    layout();
    update();
  }
}

void FlatView::drag(QPointF pos) {
  // Inside the picture's frame.
  pos.setX(std::clamp(pos.x(), frame_.target.left(), frame_.target.right()));
  pos.setY(std::clamp(pos.y(), frame_.target.top(), frame_.target.bottom()));
  const glm::vec2 p = frame_.unmap(pos);
  if (drag_ == Drag::origin) {
    origin_ = p;
  } else {
    const glm::vec2 d = p - origin_;
    if (glm::length(d) < 1e-6f * (still_.hi.x - still_.lo.x)) return;  // at the origin: no direction
    direction_ = glm::normalize(d);
  }
  Q_EMIT rayMoved(QPointF(origin_.x, origin_.y), QPointF(direction_.x, direction_.y));
  update();
}

int FlatView::nodeAt(glm::vec2 p) const {
  if (!hasOutline_ || !tree_) return -1;
  // Every region holding p, the deepest first; the selected one's next (its parent) when it is among them.
  std::vector<const OutlineRegion*> holding;
  for (const OutlineRegion& r : outline_.regions)
    if (contains(r.polygon, p)) holding.push_back(&r);
  if (holding.empty()) return -1;
  std::stable_sort(holding.begin(), holding.end(),
                   [](const OutlineRegion* a, const OutlineRegion* b) { return a->depth > b->depth; });
  const int sel = session_->selectedNode();
  for (size_t i = 0; i < holding.size(); ++i)
    if (holding[i]->node == sel) return holding[(i + 1) % holding.size()]->node;  // up; past the root: the leaf
  return holding[0]->node;
}

void FlatView::setBuildSoFar(bool on) { buildBox_->setChecked(on); }
bool FlatView::buildSoFar() const { return buildBox_->isChecked(); }
void FlatView::setCroftonLines(bool on) { linesBox_->setChecked(on); }
bool FlatView::croftonLines() const { return linesBox_->isChecked(); }

Figure FlatView::figure() const {
  const SceneData* scene = session_->scene();
  if (!scene) throw InputError("", 0, "no scene open");
  FlatFigureInput in;
  in.scene = &scene->scene;
  in.outline = outline();
  Trace one;
  if (const TracedRay* r = session_->ray(); r && rayInPlane()) {
    one = *session_->trace();
    one.rays = {*r};
    in.trace = &one;
    in.step = session_->step();
  }
  return flat_figure(in);
}

QJsonObject FlatView::dumpState() const {
  QJsonObject o;
  o["visible"] = isVisible();
  o["origin"] = QJsonArray{double(origin_.x), double(origin_.y)};
  o["direction"] = QJsonArray{double(direction_.x), double(direction_.y)};
  const QPointF px = frame_.map(origin_);
  o["origin_px"] = QJsonArray{px.x(), px.y()};
  o["frame_px"] = QJsonArray{frame_.target.left(), frame_.target.top(), frame_.target.width(), frame_.target.height()};
  o["ray_in_plane"] = rayInPlane();
  QJsonArray caption;
  for (const std::string& line : walk_.caption) caption.append(QString::fromStdString(line));
  o["caption"] = caption;
  std::map<std::string, int> marks;
  for (const FigureLayer* layer : {&walk_.walk, &walk_.marks, &walk_.ray})
    for (const FigureItem& it : layer->items) ++marks[it.css];
  QJsonObject m;
  for (const auto& [css, n] : marks) m[QString::fromStdString(css)] = n;
  o["walk_items"] = m;
  o["structure"] = hasOutline_ ? QString::fromStdString(outline_.kind) : QString();
  o["still_items"] = [&] {
    int n = 0;
    for (const FigureLayer& l : still_.layers) n += int(l.items.size());
    return n;
  }();
  o["tree_shown"] = !treeRect_.isNull();
  o["selected_node"] = session_->selectedNode();
  if (const int sel = session_->selectedNode();
      hasOutline_ && sel >= 0 && size_t(sel) < outline_.regions.size() && outline_.regions[size_t(sel)].node == sel) {
    QJsonArray poly;
    for (const glm::vec2& q : outline_.regions[size_t(sel)].polygon) poly.append(QJsonArray{q.x, q.y});
    o["selected_region"] = poly;
  }
  o["build_so_far"] = buildBox_->isChecked();
  o["anti_aliasing"] = aaBox_->isChecked();
  if (aa_)
    o["aa"] = QJsonObject{{"pixels", aa_->pixels},
                          {"samples", double(aa_->samples)},
                          {"exact", aa_->exact},
                          {"mean_abs_error", aa_->mean_abs_error},
                          {"max_abs_error", aa_->max_abs_error},
                          {"spec", aaSpec_}};
  if (croftonNode_ >= 0) {
    QJsonArray share, ratio;
    for (double v : crofton_.share) share.append(v);
    for (double v : crofton_.ratio) ratio.append(v);
    o["crofton"] = QJsonObject{{"node", croftonNode_},
                               {"meeting_node", int(crofton_.meeting_node)},
                               {"share", share},
                               {"ratio", ratio},
                               {"lines_drawn", int(crofton_.kept.size())}};
  }
  o["problem"] = problem_;
  return o;
}

}  // namespace raystep::viz
