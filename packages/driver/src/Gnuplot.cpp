#include "gphr/driver/Gnuplot.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "gphr/core/Error.hpp"

extern char** environ;

namespace gphr {

bool haveGnuplot() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0) return true;
  }
  return false;
}

std::string gnuplotQuoted(const std::string& text) {
  GPHR_REQUIRE(text.find_first_of("\n\r") == std::string::npos, InputError, "'", text,
               "' holds a line break: it cannot be named in a gnuplot script; allowed: names without one");
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

namespace {
// Whether `png` ends with the IEND chunk (length 0, "IEND", its CRC), as every complete PNG does.
bool wholePng(const std::string& png) {
  static const unsigned char kIend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  std::ifstream in(png, std::ios::binary | std::ios::ate);
  if (!in || in.tellg() < 12) return false;
  in.seekg(-12, std::ios::end);
  unsigned char tail[12] = {};
  in.read(reinterpret_cast<char*>(tail), 12);
  return in.good() && std::memcmp(tail, kIend, 12) == 0;
}

// gnuplot's exit status, or -1 when it could not be started; stdout and stderr to /dev/null.
int spawnGnuplot(const std::string& script) {
  posix_spawn_file_actions_t io;
  posix_spawn_file_actions_init(&io);
  posix_spawn_file_actions_addopen(&io, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&io, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::string program = "gnuplot", file = script;
  char* argv[] = {program.data(), file.data(), nullptr};
  pid_t pid = 0;
  const int started = posix_spawnp(&pid, "gnuplot", &io, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&io);
  if (started != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
}  // namespace

bool runGnuplot(const std::string& script, const std::vector<std::string>& pngs) {
  const int rc = spawnGnuplot(script);
  std::remove(script.c_str());
  bool whole = rc == 0;
  for (const std::string& png : pngs)
    if (!wholePng(png)) {
      std::remove(png.c_str());
      whole = false;
    }
  return whole;
}

}  // namespace gphr
