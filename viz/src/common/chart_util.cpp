#include "common/chart_util.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <QVTKOpenGLNativeWidget.h>
#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkVector.h>

namespace raystep::viz::chartutil {

vtkSmartPointer<vtkTable> makeTable(const char* xName, const char* yName) {
  auto t = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkFloatArray> x, y;
  x->SetName(xName);
  y->SetName(yName);
  t->AddColumn(x);
  t->AddColumn(y);
  return t;
}

void addRow(vtkTable* t, double x, double y) {
  vtkIdType r = t->InsertNextBlankRow();
  t->SetValue(r, 0, vtkVariant(float(x)));
  t->SetValue(r, 1, vtkVariant(float(y)));
}

std::string tickLabel(double v) {
  std::ostringstream s;
  if (v >= 1.0 && v < 1e7) {
    s.setf(std::ios::fixed);  // 1000, not 1e+03
    s.precision(0);
  } else {
    s.precision(3);
  }
  s << v;
  return s.str();
}

void setLogRange(vtkAxis* axis, double lo, double hi) {
  if (!(lo > 0.0) || !(hi > 0.0)) lo = 1.0, hi = 10.0;
  if (hi < lo) std::swap(lo, hi);
  double l0 = std::log10(lo) - 0.2, l1 = std::log10(hi) + 0.2;
  if (l1 - l0 < 0.6) {  // a single value: half a decade either side
    const double mid = 0.5 * (l0 + l1);
    l0 = mid - 0.3, l1 = mid + 0.3;
  }
  axis->SetLogScale(true);
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetUnscaledRange(std::pow(10.0, l0), std::pow(10.0, l1));
  // The ticks: mantissas 1, 2, 5 (1 alone over more than three decades, 1..9 within one).
  const double decades = l1 - l0;
  std::vector<int> mantissas = decades > 3     ? std::vector<int>{1}
                               : decades > 1.2 ? std::vector<int>{1, 2, 5}
                                               : std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9};
  vtkNew<vtkDoubleArray> positions;
  vtkNew<vtkStringArray> labels;
  for (int k = int(std::floor(l0)); k <= int(std::ceil(l1)); ++k)
    for (int m : mantissas) {
      const double v = m * std::pow(10.0, k);
      const double lv = std::log10(v);
      if (lv < l0 || lv > l1) continue;
      // In log mode the axis runs over the exponents: positions are log10 of the values.
      positions->InsertNextValue(lv);
      labels->InsertNextValue(tickLabel(v));
    }
  axis->SetCustomTickPositions(positions, labels);
}

void setLinearRange(vtkAxis* axis, double lo, double hi) {
  if (!(hi > lo)) hi = lo + 1.0;
  const double pad = 0.05 * (hi - lo);
  axis->SetLogScale(false);
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetCustomTickPositions(nullptr, nullptr);
  axis->SetRange(lo - pad, hi + pad);
}

void showContextView(QVTKOpenGLNativeWidget* widget, vtkGenericOpenGLRenderWindow* window,
                     vtkContextView* view) {
  window->SetMultiSamples(0);
  widget->setRenderWindow(window);
  view->SetRenderWindow(window);
  view->SetInteractor(widget->interactor());
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
}

void addChartMatrix2x2(vtkContextView* view, vtkChartMatrix* matrix, vtkChartXY* charts[4]) {
  view->GetScene()->AddItem(matrix);
  matrix->SetSize(vtkVector2i(2, 2));
  matrix->SetGutter(vtkVector2f(70.f, 70.f));
  matrix->SetBorders(60, 50, 20, 30);
  // The matrix counts cells from the bottom left.
  for (int i = 0; i < 4; ++i)
    charts[i] = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(i % 2, 1 - i / 2)));
}

void styleChart(vtkChartXY* chart, const char* title, const char* xTitle, const char* yTitle,
                const ChartStyle& style) {
  if (title) chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(style.titleSize);
  chart->GetTitleProperties()->SetBold(true);
  chart->SetShowLegend(style.legend);
  chart->GetLegend()->GetLabelProperties()->SetFontSize(style.legendSize);
  chart->GetLegend()->SetHorizontalAlignment(style.legendAlignment);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  if (xTitle) chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(xTitle);
  if (yTitle) chart->GetAxis(vtkAxis::LEFT)->SetTitle(yTitle);
  for (int a : {vtkAxis::BOTTOM, vtkAxis::LEFT}) {
    chart->GetAxis(a)->GetTitleProperties()->SetFontSize(style.axisTitleSize);
    chart->GetAxis(a)->GetLabelProperties()->SetFontSize(style.labelSize);
  }
}

}  // namespace raystep::viz::chartutil
