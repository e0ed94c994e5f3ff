// What the debugger's charts share (the report views; sah_chart.cpp its tables): the set-up of a chart view,
// their colours (Okabe and Ito's set, apart for colour-blind readers), tables of (x, y) points, and log axes
// with ticks a student can read (1, 2, 5 x 10^k). Included only by the charts' .cpp files, so the views' own
// headers name no VTK type.
#pragma once

#include <QColor>
#include <string>

class QVTKOpenGLNativeWidget;
class vtkAxis;
class vtkChartMatrix;
class vtkChartXY;
class vtkContextView;
class vtkGenericOpenGLRenderWindow;
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

// A chart view drawn in the widget: the window (no multisampling, which llvmpipe renders slowly) shown by the
// widget, the view drawing into it on white, driven by the widget's interactor.
void showContextView(QVTKOpenGLNativeWidget* widget, vtkGenericOpenGLRenderWindow* window,
                     vtkContextView* view);
// A 2 x 2 matrix of charts in the view, with room between them for the axis titles; charts[i] in reading
// order (top left, top right, bottom left, bottom right).
void addChartMatrix2x2(vtkContextView* view, vtkChartMatrix* matrix, vtkChartXY* charts[4]);
// The reports' chart look: a bold title, axis titles and tick labels in these font sizes, the legend shown
// (when asked) at the top, right or centred (horizontal: a vtkChartLegend alignment).
struct ChartStyle {
  int titleSize = 13;
  int axisTitleSize = 11;
  int labelSize = 10;
  bool legend = true;
  int legendSize = 11;
  int legendAlignment = 0;  // vtkChartLegend::CENTER etc.; 0 = LEFT
};
void styleChart(vtkChartXY* chart, const char* title, const char* xTitle, const char* yTitle,
                const ChartStyle& style);

}  // namespace chartutil
}  // namespace raystep::viz
