// vgroove support: output files that are whole or absent, and never in the wrong place. --out PATH:
// nothing there, or a regular file with --force: written to TARGET.vgroove-tmp.PID beside it and
// renamed into place (no truncated report; permission bits kept); a character device or FIFO:
// written through; a symbolic link: followed (a dangling one refused); a directory, block device,
// socket or one of the run's own inputs: refused. An unwritable place is found before any work
// (a temporary file is created and removed first); temporaries of dead processes are removed.
// Tests: tests/support/atomic_file_test.cpp (AtomicFile.WritesANewFile,
// AtomicFile.RefusesToOverwriteWithoutForce, AtomicFile.CharacterDevicesAreWrittenThrough,
// AtomicFile.SymbolicLinksAreFollowed, AtomicFile.DanglingLinksAreRefused, AtomicFile.InputsAreNotOverwritten,
// AtomicFile.UncreatableTargetsAreFoundByTheCheck, AtomicFile.TemporariesOfDeadProcessesAreRemoved).
// Details: docs/derivations/atomic_file.md.
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
