#include "chart_util.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <vtkAxis.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

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

}  // namespace raystep::viz::chartutil
