#include "vgroove/support/std_streams.h"

#include <fcntl.h>
#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

namespace vgroove::support {

void guard_standard_descriptors() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    // open() returns the lowest free descriptor: this one. Input is opened write-only and the
    // outputs read-only, so every use of the closed stream still fails.
    const int got = ::open("/dev/null", fd == 0 ? O_WRONLY : O_RDONLY);
    if (got >= 0 && got != fd) ::close(got);
  }
}

std::string flush_standard_output() {
  errno = 0;
  std::cout.flush();
  const bool cout_bad = !std::cout.good();
  const int flush = std::fflush(stdout);
  const int e = errno;
  if (flush == 0 && !std::ferror(stdout) && !cout_bad) return "";
  std::clearerr(stdout);
  std::cout.clear();
  return std::string("standard output: write failed") + (e ? std::string(" (") + std::strerror(e) + ")" : "");
}

}  // namespace vgroove::support
