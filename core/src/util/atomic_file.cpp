#include "raystep/util/atomic_file.h"

#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "raystep/util/error.h"

namespace raystep {

namespace {

// The temporary files open now, where a signal handler can read them: fixed slots (no allocation), each
// published with a release store once its path is complete. A path too long for a slot is not registered.
struct PendingSlot {
  std::atomic<int> state{0};  // 0 free, 1 being written, 2 holds a path
  char path[4096];
};
PendingSlot pending[16];

int register_pending(const std::string& path) {
  if (path.size() >= sizeof pending[0].path) return -1;
  for (PendingSlot& p : pending) {
    int expected = 0;
    if (p.state.compare_exchange_strong(expected, 1, std::memory_order_acquire)) {
      std::memcpy(p.path, path.c_str(), path.size() + 1);
      p.state.store(2, std::memory_order_release);
      return int(&p - pending);
    }
  }
  return -1;
}

void unregister_pending(int slot) {
  if (slot >= 0) pending[slot].state.store(0, std::memory_order_release);
}

extern "C" void remove_pending_and_reraise(int sig) {
  for (PendingSlot& p : pending)
    if (p.state.load(std::memory_order_acquire) == 2) ::unlink(p.path);  // async-signal-safe
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

void remove_temporary_files_on_signals() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, remove_pending_and_reraise);
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  temp_ = path_ + ".tmp." + std::to_string(::getpid());
  slot_ = register_pending(temp_);
}

AtomicFile::~AtomicFile() {
  if (!committed_) std::remove(temp_.c_str());
  unregister_pending(slot_);
}

void AtomicFile::commit() {
  if (std::rename(temp_.c_str(), path_.c_str()) != 0)
    throw InputError(path_, 0, std::string("cannot write: ") + std::strerror(errno));
  committed_ = true;
  unregister_pending(slot_);
  slot_ = -1;
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temp_path(), std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, 0, std::string("cannot write: ") + std::strerror(errno));
    write(out);
    out.flush();
    if (!out) throw InputError(path, 0, "write failed");
  }
  file.commit();
}

}  // namespace raystep
