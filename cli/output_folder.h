// An output folder written atomically (the report commands, export-vtk): everything goes into DIR.tmp.PID
// beside it, which replaces DIR at commit(). A failed or interrupted run (Ctrl-C included) removes its
// temporary folder and leaves DIR as it was.
#pragma once

#include <memory>
#include <string>

#include "raystep/util/atomic_file.h"

namespace raystep::cli {

class ReportFolder {
 public:
  // Throws InputError for an empty name, a missing parent folder, or an existing file (not folder) DIR.
  explicit ReportFolder(std::string dir);
  ~ReportFolder();
  ReportFolder(const ReportFolder&) = delete;
  ReportFolder& operator=(const ReportFolder&) = delete;
  const std::string& path() const { return temp_; }  // where to write until commit()
  std::string file(const std::string& name) const;
  void commit();

 private:
  std::string dir_, temp_;
  bool committed_ = false;
  std::unique_ptr<TemporaryFolderOnSignal> on_signal_;  // Ctrl-C removes the temporary folder too
};

}  // namespace raystep::cli
