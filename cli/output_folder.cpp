#include "output_folder.h"

#include <unistd.h>

#include <filesystem>

#include "raystep/util/error.h"

namespace raystep::cli {

namespace fs = std::filesystem;

ReportFolder::ReportFolder(std::string dir) : dir_(std::move(dir)) {
  while (dir_.size() > 1 && dir_.back() == '/') dir_.pop_back();
  if (dir_.empty()) throw InputError("", 0, "-o: an empty folder name");
  fs::path parent = fs::path(dir_).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw InputError(dir_, 0, "cannot write: folder '" + parent.string() + "' does not exist");
  if (fs::exists(dir_) && !fs::is_directory(dir_))
    throw InputError(dir_, 0, "cannot write the output folder: a file of that name exists");
  temp_ = dir_ + ".tmp." + std::to_string(::getpid());
  std::error_code ec;
  fs::remove_all(temp_, ec);
  if (!fs::create_directory(temp_, ec)) throw InputError(temp_, 0, "cannot create the output folder");
  on_signal_ = std::make_unique<TemporaryFolderOnSignal>(temp_);
}

ReportFolder::~ReportFolder() {
  std::error_code ec;
  if (!committed_) fs::remove_all(temp_, ec);
}

std::string ReportFolder::file(const std::string& name) const {
  return (fs::path(temp_) / name).string();
}

void ReportFolder::commit() {
  std::error_code ec;
  const std::string old = dir_ + ".old." + std::to_string(::getpid());
  bool had_old = fs::exists(dir_);
  if (had_old) fs::rename(dir_, old, ec);
  if (ec) throw InputError(dir_, 0, "cannot replace the old folder: " + ec.message());
  fs::rename(temp_, dir_, ec);
  if (ec) throw InputError(dir_, 0, "cannot move the folder into place: " + ec.message());
  committed_ = true;
  on_signal_->release();
  if (had_old) fs::remove_all(old, ec);
}

}  // namespace raystep::cli
