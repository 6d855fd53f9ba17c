#include "vgroove/support/format.h"

#include <cstdarg>
#include <cstdio>

namespace vgroove::support {

std::string format(const char* fmt, ...) {
  std::va_list args;
  va_start(args, fmt);
  std::va_list again;
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, fmt, args);
  va_end(args);
  std::string out;
  if (n > 0) {
    out.resize(static_cast<std::size_t>(n));
    // vsnprintf writes n characters and the terminating NUL, which lands on out[n] (kept by std::string).
    std::vsnprintf(out.data(), out.size() + 1, fmt, again);
  }
  va_end(again);
  return out;
}

}  // namespace vgroove::support
