#include "compare/cost_chart.h"

#include <algorithm>

#include <QJsonArray>
#include <QVBoxLayout>

#include <QVTKOpenGLNativeWidget.h>
#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkVariant.h>

#include "common/chart_util.h"

namespace raystep::viz {

struct CostChart::Impl {
  QVTKOpenGLNativeWidget* widget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkContextView> view;
  vtkNew<vtkChartXY> chart;
  std::vector<Series> series;
  vtkSmartPointer<vtkTable> marker;
  double markerT = 0.0, yMax = 1.0;
};

CostChart::CostChart(QWidget* parent) : QWidget(parent), d_(new Impl) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  Impl& d = *d_;
  d.widget = new QVTKOpenGLNativeWidget(this);
  d.widget->setMinimumSize(320, 200);
  d.window->SetMultiSamples(0);  // exact colours
  d.widget->setRenderWindow(d.window);
  d.view->SetRenderWindow(d.window);
  d.view->SetInteractor(d.widget->interactor());
  d.view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  d.view->GetScene()->AddItem(d.chart);
  d.chart->SetShowLegend(true);
  d.chart->GetLegend()->SetInline(true);  // top left: the lines start low there, so it hides nothing
  d.chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::LEFT);
  d.chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  d.chart->GetLegend()->GetLabelProperties()->SetFontSize(12);
  d.chart->GetTitleProperties()->SetFontSize(12);
  d.chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("ray parameter t");
  d.chart->GetAxis(vtkAxis::LEFT)->SetTitle("cost so far");
  for (int a : {vtkAxis::BOTTOM, vtkAxis::LEFT}) {
    d.chart->GetAxis(a)->GetTitleProperties()->SetFontSize(12);
    d.chart->GetAxis(a)->GetLabelProperties()->SetFontSize(11);
  }
  layout->addWidget(d.widget);
}

CostChart::~CostChart() = default;

void CostChart::setSeries(std::vector<Series> series, double tStart, double tEnd, const QString& title) {
  Impl& d = *d_;
  d.chart->ClearPlots();
  d.series = std::move(series);
  d.yMax = 1.0;
  for (const Series& s : d.series) {
    auto t = chartutil::makeTable("t", "cost");
    for (const auto& [x, y] : s.points) {
      chartutil::addRow(t, x, y);
      d.yMax = std::max(d.yMax, y);
    }
    vtkPlot* p = d.chart->AddPlot(vtkChart::LINE);
    p->SetInputData(t, 0, 1);
    p->SetColor(uchar(s.color.red()), uchar(s.color.green()), uchar(s.color.blue()), 255);
    p->SetWidth(2.5f);
    p->SetLabel(s.name.toStdString());
    p->SetTooltipLabelFormat("%l: cost %y at t = %x");
  }
  // The marker: a vertical line across the whole range, a plot of its own (kept out of the legend's way by an
  // empty label is not possible in VTK, so it is named for what it is).
  d.marker = chartutil::makeTable("t", "cost");
  chartutil::addRow(d.marker, d.markerT, 0.0);
  chartutil::addRow(d.marker, d.markerT, d.yMax * 1.05);
  vtkPlot* m = d.chart->AddPlot(vtkChart::LINE);
  m->SetInputData(d.marker, 0, 1);
  m->SetColor(0, 0, 0, 255);
  m->SetWidth(1.5f);
  m->GetPen()->SetLineType(vtkPen::DASH_LINE);
  m->SetLabel("t of the slider");
  chartutil::setLinearRange(d.chart->GetAxis(vtkAxis::BOTTOM), tStart, tEnd);
  vtkAxis* left = d.chart->GetAxis(vtkAxis::LEFT);
  left->SetBehavior(vtkAxis::FIXED);
  left->SetRange(0.0, d.yMax * 1.08);
  d.chart->SetTitle(title.toStdString());
  setMarker(d.markerT);
}

void CostChart::setMarker(double t) {
  Impl& d = *d_;
  d.markerT = t;
  if (!d.marker) return;
  d.marker->SetValue(0, 0, vtkVariant(float(t)));
  d.marker->SetValue(1, 0, vtkVariant(float(t)));
  d.marker->SetValue(1, 1, vtkVariant(float(d.yMax * 1.05)));
  d.marker->Modified();
  renderNow();
}

void CostChart::renderNow() {
  d_->window->Render();
}

QImage CostChart::grabChart() {
  return d_->widget->grabFramebuffer();
}

QJsonObject CostChart::dumpState() const {
  const Impl& d = *d_;
  QJsonObject o;
  QPoint off = d.widget->mapTo(window(), QPoint(0, 0));
  o["viewport"] = QJsonArray{off.x(), off.y(), d.widget->width(), d.widget->height()};
  QJsonArray lines;
  for (const Series& s : d.series) {
    QJsonArray pts;
    for (const auto& [x, y] : s.points) pts.append(QJsonArray{x, y});
    lines.append(QJsonObject{{"name", s.name},
                             {"color", QJsonArray{s.color.red(), s.color.green(), s.color.blue()}},
                             {"points", pts}});
  }
  o["lines"] = lines;
  o["marker_t"] = d.markerT;
  o["plots"] = int(d.chart->GetNumberOfPlots());
  return o;
}

}  // namespace raystep::viz
