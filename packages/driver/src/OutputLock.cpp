#include "gphr/driver/OutputLock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

#include "gphr/core/Error.hpp"
#include "gphr/driver/OutputDirectory.hpp"

namespace gphr {

namespace {

std::string hostName() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  return host;
}

// The owner line another process wrote into the lock file (best effort, for the message).
std::string ownerOf(int fd) {
  char buf[512] = {0};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  std::string s = n > 0 ? std::string(buf, static_cast<size_t>(n)) : "";
  while (!s.empty() && (s.back() == '\n' || s.back() == '\0')) s.pop_back();
  return s.empty() ? "another gphr process" : s;
}

// Rank 0: flock the lock file; the path must still name the locked file afterwards (a releasing
// owner removes it: then lock the new one). Returns the open descriptor, or -1 with `error` set.
int acquire(const std::string& path, const std::string& command, std::string& error) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      error = detail::concat("cannot create the lock file '", path, "': ", std::strerror(errno));
      return -1;
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      error = detail::concat("output directory is in use: '", path, "' is held by ", ownerOf(fd),
                             "; allowed: one gphr command per output directory at a time");
      close(fd);
      return -1;
    }
    struct stat held {}, named {};
    if (fstat(fd, &held) == 0 && stat(path.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      char line[512];
      const std::time_t now = std::time(nullptr);
      char when[64];
      std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
      const int len = std::snprintf(line, sizeof line, "gphr %s (pid %ld on host %s, since %s)\n", command.c_str(),
                                    static_cast<long>(getpid()), hostName().c_str(), when);
      if (ftruncate(fd, 0) != 0 || pwrite(fd, line, static_cast<size_t>(len), 0) != len) {
        error = detail::concat("cannot write the lock file '", path, "': ", std::strerror(errno));
        close(fd);
        return -1;
      }
      return fd;
    }
    close(fd);  // removed or replaced between open and flock: try the file that is there now
  }
  error = detail::concat("cannot take the lock file '", path, "': it keeps being replaced");
  return -1;
}

}  // namespace

OutputLock::OutputLock(const std::string& dir, const std::string& command, const RCP<const Comm>& comm)
    : path_(dir + "/.gphr.lock") {
  std::string error;
  if (comm->getRank() == 0) fd_ = acquire(path_, command, error);
  agreeOnError(comm, error);  // every rank ends with rank 0's message
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  unlink(path_.c_str());  // before the release: a waiting process then locks a new file
  close(fd_);
}

}  // namespace gphr
