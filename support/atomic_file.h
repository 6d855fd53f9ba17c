// vgroove support: output files that are whole or absent.
//
// The text goes to a temporary file beside the target, which is then renamed over it: a run that
// fails or is interrupted never leaves a truncated report. An existing file is replaced only
// when the caller says so (--force).
#pragma once

#include <string>

namespace vgroove::support {

// Throws UserError if `path` exists and !overwrite, or if the file cannot be written.
void check_writable_target(const std::string& path, bool overwrite);
void write_file_atomically(const std::string& path, const std::string& text, bool overwrite);

}  // namespace vgroove::support
