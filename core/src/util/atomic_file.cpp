#include "raystep/util/atomic_file.h"

#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
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
  std::atomic<int> state{0};  // 0 free, 1 being written, 2 holds a file's path, 3 a folder's
  char path[4096];
};
PendingSlot pending[16];

int register_pending(const std::string& path, bool folder = false) {
  if (path.size() >= sizeof pending[0].path) return -1;
  for (PendingSlot& p : pending) {
    int expected = 0;
    if (p.state.compare_exchange_strong(expected, 1, std::memory_order_acquire)) {
      std::memcpy(p.path, path.c_str(), path.size() + 1);
      p.state.store(folder ? 3 : 2, std::memory_order_release);
      return int(&p - pending);
    }
  }
  return -1;
}

void unregister_pending(int slot) {
  if (slot >= 0) pending[slot].state.store(0, std::memory_order_release);
}

// A directory entry as the getdents64 system call returns it (linux_dirent64).
struct DirEntry64 {
  uint64_t ino;
  int64_t off;
  unsigned short reclen;
  unsigned char type;
  char name[1];
};

// Removes `name` (relative to the open folder `at`, or a path with AT_FDCWD) and, if it is a folder, what it
// holds, `depth` levels of subfolders deep. Only system calls a signal handler may make: openat, getdents64,
// lseek, unlinkat, close. Entries are read again from the start after each pass that removed any, since a
// removal may move the rest of a folder's listing.
void remove_tree(int at, const char* name, int depth) {
  if (::unlinkat(at, name, 0) == 0) return;  // a file (or a link)
  const int fd = ::openat(at, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) {
    alignas(8) char buf[4096];
    for (int pass = 0; pass < 64; ++pass) {
      bool removed = false;
      ::lseek(fd, 0, SEEK_SET);
      for (long n; (n = ::syscall(SYS_getdents64, fd, buf, sizeof buf)) > 0;)
        for (long at_byte = 0; at_byte < n;) {
          const auto* e = reinterpret_cast<const DirEntry64*>(buf + at_byte);
          at_byte += e->reclen;
          if (e->name[0] == '.' && (e->name[1] == 0 || (e->name[1] == '.' && e->name[2] == 0))) continue;
          if (::unlinkat(fd, e->name, 0) == 0) {
            removed = true;
          } else if (depth > 0) {
            remove_tree(fd, e->name, depth - 1);
            removed = true;
          }
        }
      if (!removed) break;
    }
    ::close(fd);
  }
  ::unlinkat(at, name, AT_REMOVEDIR);
}

extern "C" void remove_pending_and_reraise(int sig) {
  for (PendingSlot& p : pending) {
    const int state = p.state.load(std::memory_order_acquire);
    if (state == 2) ::unlink(p.path);  // async-signal-safe
    if (state == 3) remove_tree(AT_FDCWD, p.path, 4);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

void remove_temporary_files_on_signals() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, remove_pending_and_reraise);
}

TemporaryFolderOnSignal::TemporaryFolderOnSignal(const std::string& path) : slot_(register_pending(path, true)) {}

void TemporaryFolderOnSignal::release() {
  unregister_pending(slot_);
  slot_ = -1;
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
