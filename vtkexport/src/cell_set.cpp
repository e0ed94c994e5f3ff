#include "raystep/vtk_export/cell_set.h"

#include <limits>

namespace raystep::vtk_export {

namespace {
double missing(bool integer) {
  return integer ? -1.0 : std::numeric_limits<double>::quiet_NaN();
}
}  // namespace

CellArray& CellSet::array(const std::string& name, bool integer) {
  for (CellArray& a : arrays_)
    if (a.name == name) return a;
  arrays_.push_back(CellArray{name, integer, {}});
  return arrays_.back();
}

void CellSet::set(const std::string& name, double value, bool integer) {
  CellArray& a = array(name, integer);
  // The value belongs to the newest cell: cells before it that had no value for this array get "missing".
  if (size() > 0) a.values.resize(size() - 1, missing(a.integer));
  a.values.push_back(value);
}

void CellSet::finish() {
  for (CellArray& a : arrays_) a.values.resize(size(), missing(a.integer));
}

}  // namespace raystep::vtk_export
