#include "vgroove/support/user_error.h"

#include <charconv>

namespace vgroove::support {

std::string number_text(double v) {
  // The shortest text that reads back as the same double (10 -> "10", 0.1 -> "0.1").
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string interval_text(double lo, bool lo_closed, double hi, bool hi_closed) {
  return std::string(lo_closed ? "[" : "(") + number_text(lo) + ", " + number_text(hi) +
         (hi_closed ? "]" : ")");
}

}  // namespace vgroove::support
