// The side-by-side view's cost chart (lecture: the cost model, t_t per traversal step and t_i per primitive
// test): each structure's cumulative cost against the ray's parameter t, one line per structure, so that the
// class sees where one structure pulls ahead; a vertical marker at the timeline's t. VTK stays inside
// cost_chart.cpp.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include <QColor>
#include <QImage>
#include <QJsonObject>
#include <QString>
#include <QWidget>

namespace raystep::viz {

class CostChart : public QWidget {
  Q_OBJECT
 public:
  struct Series {
    QString name;
    QColor color;
    std::vector<std::pair<double, double>> points;  // (t, cost so far), a staircase
  };

  explicit CostChart(QWidget* parent = nullptr);
  ~CostChart() override;

  // The lines over t in [tStart, tEnd]; title names the cost model.
  void setSeries(std::vector<Series> series, double tStart, double tEnd, const QString& title);
  void setMarker(double t);  // the vertical line at the timeline's t
  void renderNow();
  QImage grabChart();
  // The lines (name, colour, points), the marker's t and where the chart is on screen.
  QJsonObject dumpState() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
};

}  // namespace raystep::viz
