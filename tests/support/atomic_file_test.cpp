// Tests of validation/atomic_file.h: no silent overwrite, whole files, no temporaries left behind.
#include "vgroove/support/atomic_file.h"

#include "vgroove/support/user_error.h"

#include "tests/test_files.h"

#include <gtest/gtest.h>

#include <string>

namespace vgroove::support {
namespace {

using testing_files::read_text;
using testing_files::TempDir;
using testing_files::write_text;

// No "<name>.tmp.<pid>" file may survive a write, successful or not.
void expect_no_temporaries(const TempDir& dir) {
  for (const std::string& e : dir.entries()) EXPECT_EQ(e.find(".tmp."), std::string::npos) << "left behind: " << e;
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

TEST(AtomicFile, FailedRenameLeavesNoTemporary) {
  // The target is a non-empty directory: with overwrite the rename must fail, and clean up.
  TempDir dir;
  const std::string f = dir.file("taken");
  std::filesystem::create_directory(f);
  write_text(f + "/inside", "x");
  EXPECT_THROW(write_file_atomically(f, "text", true), UserError);
  expect_no_temporaries(dir);
  EXPECT_EQ(read_text(f + "/inside"), "x");
}

}  // namespace
}  // namespace vgroove::support
