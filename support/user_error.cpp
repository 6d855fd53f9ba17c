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
  std::string s(1, lo_closed ? '[' : '(');
  s += number_text(lo);
  s += ", ";
  s += number_text(hi);
  s += hi_closed ? ']' : ')';
  return s;
}

}  // namespace vgroove::support
