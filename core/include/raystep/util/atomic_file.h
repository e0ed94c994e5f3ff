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
};

// Write through a stream callback, atomically. Throws InputError naming the path if it cannot be written.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace raystep
