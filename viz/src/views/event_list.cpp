#include "views/event_list.h"

#include <QAbstractListModel>
#include <QFont>
#include <QFontDatabase>
#include <QRegularExpression>
#include <QLabel>
#include <QListView>
#include <QResizeEvent>
#include <QVBoxLayout>

#include "app/session.h"

#include "raystep/replay/explain.h"

namespace raystep::viz {

class EventModel : public QAbstractListModel {
 public:
  using QAbstractListModel::QAbstractListModel;
  void setRay(const TracedRay* ray) {
    beginResetModel();
    ray_ = ray;
    endResetModel();
  }
  // Rows after `step` show no event (-1: all shown): the quiz asks what comes next.
  void setConcealAfter(int step) {
    if (step == concealAfter_) return;
    concealAfter_ = step;
    if (rowCount() > 0) Q_EMIT dataChanged(index(0), index(rowCount() - 1));
  }
  int rowCount(const QModelIndex& = {}) const override { return ray_ ? int(ray_->events.size()) : 0; }
  QVariant data(const QModelIndex& index, int role) const override {
    if (!ray_ || index.row() >= int(ray_->events.size())) return {};
    if (concealAfter_ >= 0 && index.row() > concealAfter_) {
      if (role == Qt::DisplayRole) return QString("%1  ?").arg(index.row());
      if (role == Qt::ForegroundRole) return QColor(150, 150, 150);
      return {};
    }
    const Event& e = ray_->events[size_t(index.row())];
    if (role == Qt::DisplayRole) {
      QString line = QString::fromStdString(replay::describe_event(e));
      if (concealAfter_ >= 0 && index.row() == concealAfter_) line.remove(QRegularExpression("\\s+next \\w+$"));
      return line;
    }
    if (role == Qt::ForegroundRole) {
      switch (e.type) {
        case EventType::cell: return QColor(90, 140, 255);
        case EventType::prim_test: return e.hit ? QColor(40, 170, 60) : QColor(200, 50, 50);
        case EventType::mailbox_hit: return QColor(150, 80, 230);
        case EventType::box_test:
          return e.hit ? QColor(215, 120, 0) : QColor(130, 130, 130);  // BVH: a child's box
        case EventType::skip:
          return QColor(90, 140, 50);  // BVH: popped, beyond the nearest hit
        case EventType::hit_accepted:
        case EventType::hit_deferred: return QColor(220, 40, 170);
        default: return {};
      }
    }
    return {};
  }

 private:
  const TracedRay* ray_ = nullptr;
  int concealAfter_ = -1;
};

EventList::EventList(Session* session, QWidget* parent) : QWidget(parent), session_(session) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(new QLabel(tr("<b>Events</b>")));
  model_ = new EventModel(this);
  view_ = new QListView;
  view_->setObjectName("eventList");
  view_->setModel(model_);
  view_->setUniformItemSizes(true);  // fast with 100,000 rows
  view_->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  view_->setSelectionMode(QAbstractItemView::SingleSelection);
  view_->setFocusPolicy(Qt::NoFocus);
  layout->addWidget(view_);
  connect(view_, &QListView::clicked, this, [this](const QModelIndex& i) { session_->setStep(i.row()); });
  connect(session_, &Session::traceChanged, this, [this] {
    model_->setRay(session_->ray());
    sync();
  });
  connect(session_, &Session::stepChanged, this, &EventList::sync);
}

void EventList::setConcealAfter(int step) { model_->setConcealAfter(step); }

void EventList::setScale(double scale) {
  QFont f = QFontDatabase::systemFont(QFontDatabase::FixedFont);
  if (f.pointSizeF() > 0) f.setPointSizeF(f.pointSizeF() * scale);
  view_->setFont(f);
}

int EventList::currentRow() const { return view_->currentIndex().row(); }

void EventList::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  if (view_->currentIndex().isValid())
    view_->scrollTo(view_->currentIndex(), QAbstractItemView::PositionAtCenter);
}

void EventList::sync() {
  if (model_->rowCount() == 0) return;
  QModelIndex i = model_->index(session_->step());
  view_->setCurrentIndex(i);
  view_->scrollTo(i, QAbstractItemView::PositionAtCenter);
}

}  // namespace raystep::viz
