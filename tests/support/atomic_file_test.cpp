// Tests of validation/atomic_file.h: no silent overwrite, whole files, no temporaries left behind.
#include "vgroove/support/atomic_file.h"

#include "vgroove/support/user_error.h"

#include "tests/test_files.h"
#include "tests/user_error_of.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <filesystem>
#include <string>
#include <thread>

namespace vgroove::support {
namespace {

using testing_files::read_text;
using testing_files::TempDir;
using testing_files::type_of;
using testing_files::user_error_of;
using testing_files::write_text;

// No "<name>.vgroove-tmp.<pid>" file may survive a write, successful or not.
void expect_no_temporaries(const TempDir& dir) {
  for (const std::string& e : dir.entries())
    EXPECT_EQ(e.find("vgroove-tmp"), std::string::npos) << "left behind: " << e;
}

TEST(AtomicFile, WritesANewFile) {
  TempDir dir;
  const std::string f = dir.file("report.json");
  write_file_atomically(f, "{\"a\": 1}\n", false);
  EXPECT_EQ(read_text(f), "{\"a\": 1}\n");
  EXPECT_EQ(dir.entries().size(), 1u);
  expect_no_temporaries(dir);
}

TEST(AtomicFile, RefusesToOverwriteWithoutForce) {
  TempDir dir;
  const std::string f = dir.file("report.json");
  write_text(f, "old");
  try {
    write_file_atomically(f, "new", false);
    ADD_FAILURE() << "no UserError thrown";
  } catch (const UserError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(f), std::string::npos) << m;
    EXPECT_NE(m.find("--force"), std::string::npos) << m;
  }
  EXPECT_EQ(read_text(f), "old");
  expect_no_temporaries(dir);
  EXPECT_THROW(check_writable_target(f, false), UserError);
  EXPECT_NO_THROW(check_writable_target(f, true));
}

TEST(AtomicFile, ReplacesWithOverwrite) {
  TempDir dir;
  const std::string f = dir.file("report.json");
  write_text(f, "a much longer old text than the new one");
  write_file_atomically(f, "new", true);
  EXPECT_EQ(read_text(f), "new");  // replaced whole, not written over the old bytes
  EXPECT_EQ(dir.entries().size(), 1u);
  expect_no_temporaries(dir);
}

TEST(AtomicFile, MissingDirectoryIsNamed) {
  TempDir dir;
  const std::string f = dir.file("no/such/dir/report.json");
  try {
    write_file_atomically(f, "x", false);
    ADD_FAILURE() << "no UserError thrown";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(AtomicFile, DirectoriesAreRefusedAndLeftAlone) {
  TempDir dir;
  const std::string f = dir.file("taken");
  std::filesystem::create_directory(f);
  write_text(f + "/inside", "x");
  EXPECT_CONTAINS(user_error_of([&] { write_file_atomically(f, "text", true); }), "is a directory");
  expect_no_temporaries(dir);
  EXPECT_EQ(read_text(f + "/inside"), "x");
}

TEST(AtomicFile, CharacterDevicesAreWrittenThrough) {
  // /dev/null: written, never replaced (with or without overwrite: nothing is lost).
  EXPECT_NO_THROW(check_writable_target("/dev/null", false));
  EXPECT_NO_THROW(write_file_atomically("/dev/null", "text", false));
  EXPECT_EQ(type_of("/dev/null"), static_cast<mode_t>(S_IFCHR));
  // /dev/full: the write error is reported.
  EXPECT_CONTAINS(user_error_of([] { write_file_atomically("/dev/full", std::string(100000, 'x'), true); }),
                  "/dev/full: writing failed (No space left on device)");
  EXPECT_EQ(type_of("/dev/full"), static_cast<mode_t>(S_IFCHR));
}

TEST(AtomicFile, FifosAreWrittenThrough) {
  TempDir dir;
  const std::string f = dir.file("fifo");
  ASSERT_EQ(::mkfifo(f.c_str(), 0600), 0);
  std::string got;
  std::thread reader([&] { got = read_text(f); });
  write_file_atomically(f, "through the pipe", false);
  reader.join();
  EXPECT_EQ(got, "through the pipe");
  EXPECT_EQ(type_of(f), static_cast<mode_t>(S_IFIFO));
}

TEST(AtomicFile, SymbolicLinksAreFollowed) {
  TempDir dir;
  const std::string target = dir.file("target.json"), link = dir.file("link.json");
  write_text(target, "old");
  std::filesystem::create_symlink(target, link);
  EXPECT_CONTAINS(user_error_of([&] { write_file_atomically(link, "new", false); }), "--force");
  write_file_atomically(link, "new", true);
  EXPECT_EQ(type_of(link), static_cast<mode_t>(S_IFLNK));
  EXPECT_EQ(read_text(target), "new");
  // A relative link, resolved from its own directory.
  const std::string rel = dir.file("rel.json");
  std::filesystem::create_symlink("target.json", rel);
  write_file_atomically(rel, "newer", true);
  EXPECT_EQ(read_text(target), "newer");
  EXPECT_EQ(type_of(rel), static_cast<mode_t>(S_IFLNK));
  expect_no_temporaries(dir);
}

TEST(AtomicFile, DanglingLinksAreRefused) {
  TempDir dir;
  const std::string link = dir.file("link.json"), nowhere = dir.file("nowhere.json");
  std::filesystem::create_symlink(nowhere, link);
  for (bool overwrite : {false, true})
    EXPECT_CONTAINS(user_error_of([&] { write_file_atomically(link, "x", overwrite); }),
                    "is a symbolic link to " + nowhere + ", which does not exist");
  EXPECT_FALSE(std::filesystem::exists(nowhere));
  EXPECT_EQ(type_of(link), static_cast<mode_t>(S_IFLNK));
}

TEST(AtomicFile, InputsAreNotOverwritten) {
  TempDir dir;
  const std::string in = dir.file("suite.json"), link = dir.file("alias.json");
  write_text(in, "spec");
  std::filesystem::create_symlink(in, link);
  for (const std::string& out : {in, link})
    EXPECT_CONTAINS(user_error_of([&] { check_writable_target(out, true, {in}); }), "is the input file");
  EXPECT_NO_THROW(check_writable_target(dir.file("other.json"), true, {in}));
}

TEST(AtomicFile, UncreatableTargetsAreFoundByTheCheck) {
  EXPECT_CONTAINS(user_error_of([] { check_writable_target("/proc/vgroove-probe.json", true); }),
                  "cannot create a file in the directory /proc");
  expect_no_temporaries(TempDir{});
}

TEST(AtomicFile, ReplacedFilesKeepTheirPermissions) {
  TempDir dir;
  const std::string f = dir.file("private.json");
  write_text(f, "old");
  std::filesystem::permissions(f, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  write_file_atomically(f, "new", true);
  EXPECT_EQ(std::filesystem::status(f).permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
}

TEST(AtomicFile, TemporariesOfDeadProcessesAreRemoved) {
  TempDir dir;
  const std::string f = dir.file("report.json");
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const std::string stale = temporary_name(f, dead), live = temporary_name(f, ::getppid());
  EXPECT_EQ(stale, f + ".vgroove-tmp." + std::to_string(dead));
  write_text(stale, "partial");
  write_text(live, "another run, still going");
  write_file_atomically(f, "whole", false);
  EXPECT_FALSE(std::filesystem::exists(stale));
  EXPECT_TRUE(std::filesystem::exists(live));
  EXPECT_EQ(read_text(f), "whole");
  // A target name too long for the suffix still gets a temporary of a legal length.
  const std::string longname = dir.file(std::string(250, 'n'));
  write_file_atomically(longname, "long", false);
  EXPECT_EQ(read_text(longname), "long");
}

}  // namespace
}  // namespace vgroove::support
