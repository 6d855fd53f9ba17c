// vgroove support: output files that are whole or absent, and never in the wrong place.
//
// What --out PATH does, by what PATH is (decided before the run, checked again when writing):
//   - nothing there: the text goes to a temporary file beside it, which is renamed into place
//     (a run that fails or is interrupted leaves no truncated report);
//   - a regular file: replaced the same way, and only with --force (its permission bits kept);
//   - a character device or a FIFO (/dev/null, a named pipe): written through, never replaced or
//     created; a write error (/dev/full) is reported;
//   - a symbolic link: followed, and the rules above apply to what it points to (a link to a
//     regular file keeps pointing to the new report); a dangling link is refused, not written
//     through (as GNU cp does), so that a run never creates a file somewhere the user did not name;
//   - a directory, a block device or a socket: refused;
//   - one of the run's own input files (the same file by device and inode): refused.
// Before the run a temporary file is created and removed in the target's directory, so an
// unwritable place (read-only mount, /proc, no permission) is reported before any work.
//
// Temporary files are named TARGET.vgroove-tmp.PID (TARGET's name cut to 200 bytes). One left by
// a process that no longer exists (killed between write and rename) is removed by the next run
// that writes the same target.
#pragma once

#include <string>
#include <vector>

namespace vgroove::support {

// Throws UserError if `path` cannot be written as described above: it exists and !overwrite,
// it is of a refused kind, it is the same file as one of `inputs`, or nothing can be created
// where it would go.
void check_writable_target(const std::string& path, bool overwrite, const std::vector<std::string>& inputs = {});
// Writes `text` to `path` as described above (the checks of check_writable_target, but inputs).
void write_file_atomically(const std::string& path, const std::string& text, bool overwrite);

// The temporary name used for `target` by process `pid` (for tests and documentation).
std::string temporary_name(const std::string& target, long pid);

}  // namespace vgroove::support
