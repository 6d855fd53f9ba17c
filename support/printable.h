// vgroove support: user text made safe to print on one line of a terminal.
//
// Names, paths and values come from files and command lines and may hold anything: a newline
// would split a one-line error in two, ESC would drive the terminal, bidirectional controls would
// show text in another order than it is. printable() escapes them, so what is printed is what
// the input holds, on one line.
#pragma once

#include <string>
#include <string_view>

namespace vgroove::support {

// `s` with C0 and C1 control characters, DEL, bidirectional and line/paragraph-separator
// characters and bytes that are not UTF-8 escaped: \n, \t, \r, \xNN for bytes, \u{XXXX} for
// code points. Printable UTF-8 (accents, CJK) is kept as it is.
std::string printable(std::string_view s);
// Whether s is valid UTF-8 (no overlong forms, surrogates or code points past U+10FFFF): what a
// JSON report can hold as text.
bool valid_utf8(std::string_view s);
// Throws UserError unless `path` can name a file: the system reads a name only up to a NUL byte
// (Python strings may hold one), so such a name would open another file.
void check_file_name(const std::string& path);

}  // namespace vgroove::support
