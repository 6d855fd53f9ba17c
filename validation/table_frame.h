// vgroove validation: the first and last lines that every suite kind's table shares.
//
// The title names the suite (its name through support::printable, so control characters in a
// file's name are shown escaped, never sent to the terminal), the kind, what the run did, and the
// version and thread count that made it; the closing line counts the passing cases and the wall
// time. Both are built with support::format, so a name of any length keeps its whole line.
// Tested by tests/validation/table_frame_test.cpp (every kind's printer with a hostile name).
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>

namespace vgroove::validation {

// "<name> (<kind>): <detail>, vgroove V (git G), T threads\n"; without detail,
// "<name> (<kind>): vgroove V (git G), T threads\n".
void print_table_title(std::ostream& os, std::string_view name, std::string_view kind, const std::string& detail,
                       int threads);

// "  P/N <what>; wall W s\n" ("cases pass" unless a kind counts something else).
void print_table_close(std::ostream& os, std::size_t passed, std::size_t total, double wall_s,
                       std::string_view what = "cases pass");

}  // namespace vgroove::validation
