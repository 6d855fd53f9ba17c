// vgroove support: printf-style formatting into a std::string of whatever length the text needs.
//
// Table lines hold user text (suite names, paths) of any length; a fixed buffer would cut such a
// line and lose its newline. format() sizes the string from vsnprintf's own count.
#pragma once

#include <string>

namespace vgroove::support {

// The text std::printf would print for `fmt` and its arguments, whole.
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace vgroove::support
