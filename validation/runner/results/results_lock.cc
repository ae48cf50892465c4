#include "validation/runner/results/results_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace phdslam::validation {

namespace {

// True when `fd` is still the file at `path` (another process may have removed it meanwhile).
bool StillLinked(int fd, const std::filesystem::path& path) {
  struct stat open_file {};
  struct stat named_file {};
  return ::fstat(fd, &open_file) == 0 && ::stat(path.c_str(), &named_file) == 0 &&
         open_file.st_dev == named_file.st_dev && open_file.st_ino == named_file.st_ino;
}

}  // namespace

ResultsLock::ResultsLock(const std::filesystem::path& folder) : path_(folder / kLockFile) {
  std::filesystem::create_directories(folder);
  while (true) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) {
      throw std::runtime_error("cannot create the lock file " + path_.string() + ": " +
                               std::strerror(errno));
    }
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd_);
      fd_ = -1;
      if (error == EWOULDBLOCK) {
        throw std::runtime_error(folder.string() + " is in use by another phdslam process (it " +
                                 "holds " + path_.string() +
                                 "); wait for it to finish or use another --out");
      }
      throw std::runtime_error("cannot lock " + path_.string() + ": " + std::strerror(error));
    }
    if (StillLinked(fd_, path_)) return;
    ::close(fd_);  // locked a file its holder removed on release: lock the new one
  }
}

ResultsLock::~ResultsLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still locked, so the folder is left as it was
  ::close(fd_);
}

}  // namespace phdslam::validation
