// Outputs are written atomically: to a temporary file beside the target, then renamed over it, so that a
// reader never sees a half-written file and a failed run leaves nothing behind.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace raystep {

class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();  // removes the temporary file unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& temp_path() const { return temp_; }
  const std::string& path() const { return path_; }
  void commit();  // rename the temporary file over the target; throws InputError on failure

 private:
  std::string path_, temp_;
  bool committed_ = false;
  int slot_ = -1;  // where a signal handler finds temp_ (see remove_temporary_files_on_signals)
};

// Write through a stream callback, atomically. Throws InputError naming the path if it cannot be written.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// Ctrl-C (SIGINT), SIGTERM and SIGHUP remove the temporary files of the AtomicFiles still open and the
// temporary folders still registered (TemporaryFolderOnSignal), then end the process as the signal would
// have (a shell then reports 130 for Ctrl-C): a student who stops a gigabyte-long build log or a report
// leaves no debris. Call once, early in main. (SIGKILL cannot be caught: a killed run may leave a
// PATH.tmp.PID file or folder, never a half PATH.)
void remove_temporary_files_on_signals();

// While it lives, a signal removes this folder and what it holds (up to four levels of subfolders, by
// async-signal-safe system calls only). For an output folder written as DIR.tmp.PID and renamed into place:
// release() once it is renamed, or let the destructor forget it (the folder itself is the owner's to remove).
class TemporaryFolderOnSignal {
 public:
  explicit TemporaryFolderOnSignal(const std::string& path);
  ~TemporaryFolderOnSignal() { release(); }
  TemporaryFolderOnSignal(const TemporaryFolderOnSignal&) = delete;
  TemporaryFolderOnSignal& operator=(const TemporaryFolderOnSignal&) = delete;
  void release();

 private:
  int slot_ = -1;
};

}  // namespace raystep
