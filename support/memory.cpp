#include "vgroove/support/memory.h"

#include "vgroove/support/user_error.h"

#include <sys/resource.h>
#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

namespace vgroove::support {

namespace {
// What the program needs besides its data: code and libraries.
constexpr double kProgramBytes = 64.0 * (1 << 20);
}  // namespace

double memory_limit_bytes() {
  double limit = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    struct rlimit r {};
    if (::getrlimit(resource, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
      limit = std::min(limit, static_cast<double>(r.rlim_cur));
  }
  std::ifstream cg("/sys/fs/cgroup/memory.max");
  std::string text;
  if (cg >> text && text != "max") {
    try {
      limit = std::min(limit, std::stod(text));
    } catch (const std::exception&) {
    }
  }
  return limit;
}

std::string bytes_text(double bytes) {
  char buf[32];
  if (bytes >= 1e9)
    std::snprintf(buf, sizeof buf, "%.1f GB", bytes / 1e9);
  else if (bytes >= 1e6)
    std::snprintf(buf, sizeof buf, "%.0f MB", bytes / 1e6);
  else
    std::snprintf(buf, sizeof buf, "%.1f kB", bytes / 1e3);
  return buf;
}

void check_memory(double bytes, const std::string& what, const std::string& detail) {
  const double limit = memory_limit_bytes();
  const double need = bytes + kProgramBytes;
  if (need > limit)
    throw UserError(what + " needs about " + bytes_text(need) + " of memory (" + detail + "), more than the " +
                    bytes_text(limit) + " this process may use");
}

}  // namespace vgroove::support
