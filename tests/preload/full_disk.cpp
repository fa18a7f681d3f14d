// LD_PRELOAD library for the tests: a disk that is full after LIGHTCONE_FULL_DISK_BYTES bytes.
// Writes into regular files beyond that many bytes in all are cut short, as a full disk cuts
// them, and then fail with ENOSPC; writes to anything else (terminals, pipes) pass through.
#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>

namespace {

using WriteFunction = ssize_t (*)(int, const void*, size_t);

WriteFunction real_write() {
  static const auto function = reinterpret_cast<WriteFunction>(dlsym(RTLD_NEXT, "write"));
  return function;
}

std::atomic<long long>& bytes_left() {
  static std::atomic<long long> left = [] {
    const char* budget = std::getenv("LIGHTCONE_FULL_DISK_BYTES");
    return budget != nullptr ? std::atoll(budget) : -1LL;
  }();
  return left;
}

}  // namespace

extern "C" ssize_t write(int fd, const void* data, size_t size) {
  struct stat info;
  if (bytes_left() < 0 || fstat(fd, &info) != 0 || !S_ISREG(info.st_mode))
    return real_write()(fd, data, size);
  const long long left = bytes_left().load();
  if (left == 0) {
    errno = ENOSPC;
    return -1;
  }
  const size_t allowed = static_cast<size_t>(left) < size ? static_cast<size_t>(left) : size;
  const ssize_t written = real_write()(fd, data, allowed);
  if (written > 0) bytes_left() -= written;
  return written;
}
