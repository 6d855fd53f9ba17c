// vgroove support: the one exception type for mistakes in the user's input.
//
// Thrown for bad files, JSON and command-line values; caught once in main, printed as one line
// on stderr, exit status 2. Invariants inside the library are asserts, not UserErrors.
#pragma once

#include <stdexcept>
#include <string>

namespace vgroove::support {

class UserError : public std::runtime_error {
 public:
  explicit UserError(const std::string& what) : std::runtime_error(what) {}
};

// "(0, 180]"-style interval text for messages.
std::string interval_text(double lo, bool lo_closed, double hi, bool hi_closed);
// Shortest text that reads back as the same double.
std::string number_text(double v);

}  // namespace vgroove::support
