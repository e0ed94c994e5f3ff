// What the debugger's charts share (aa_report_view.cpp, grid_sweep_view.cpp; sah_chart.cpp its tables):
// their colours (Okabe and Ito's set, apart for colour-blind readers), tables of (x, y) points, and log axes
// with ticks a student can read (1, 2, 5 x 10^k). Included only by the charts' .cpp files, so the views' own
// headers name no VTK type.
#pragma once

#include <QColor>
#include <string>

class vtkAxis;
class vtkTable;
template <class T>
class vtkSmartPointer;

namespace raystep::viz {

namespace chartcolor {
inline const QColor blue{0, 114, 178};
inline const QColor vermillion{213, 94, 0};
inline const QColor green{0, 158, 115};
inline const QColor purple{204, 121, 167};
inline const QColor orange{230, 159, 0};
inline const QColor skyBlue{86, 180, 233};
inline const QColor black{0, 0, 0};
inline const QColor grey{120, 120, 120};
}  // namespace chartcolor

namespace chartutil {

// A table of two float columns named xName and yName.
vtkSmartPointer<vtkTable> makeTable(const char* xName, const char* yName);
void addRow(vtkTable* t, double x, double y);
// A log axis over [lo, hi] (both > 0) widened by a fifth of a decade, with fixed ticks at 1, 2, 5 x 10^k
// (fewer when the range spans many decades, more when it spans less than one), labelled as plain numbers.
void setLogRange(vtkAxis* axis, double lo, double hi);
// A linear axis over [lo, hi] widened by 5%, its ticks VTK's.
void setLinearRange(vtkAxis* axis, double lo, double hi);
// A plain number for a tick label: 0.001, 0.02, 5, 200, 1e+05.
std::string tickLabel(double v);

}  // namespace chartutil
}  // namespace raystep::viz
