#include "vgroove/support/atomic_file.h"
#include "vgroove/support/printable.h"

#include "vgroove/support/user_error.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace vgroove::support {

namespace {

std::string why(int e) { return std::strerror(e); }

std::string parent_of(const std::string& path) {
  const std::string p = std::filesystem::path(path).parent_path().string();
  return p.empty() ? "." : p;
}

std::string name_of(const std::string& path) { return std::filesystem::path(path).filename().string(); }

bool same_file(const struct stat& a, const struct stat& b) { return a.st_dev == b.st_dev && a.st_ino == b.st_ino; }

enum class Kind { absent, regular, write_through };

// What writing `path` means: create `file`, replace `file` (the regular file `path` names, a
// symbolic link followed), or write through `path` (a character device or a FIFO).
struct Target {
  Kind kind = Kind::absent;
  std::string file;
  struct stat st {};
};

std::string link_text(const std::string& path) {
  std::string buf(4096, '\0');
  const ssize_t n = ::readlink(path.c_str(), buf.data(), buf.size());
  return n > 0 ? buf.substr(0, static_cast<std::size_t>(n)) : std::string("?");
}

Target classify(const std::string& path, bool overwrite) {
  if (path.empty()) throw UserError("--out: the path is empty");
  check_file_name(path);
  // "-" means standard output to most tools; here it would be a file named "-".
  if (path == "-")
    throw UserError(
        "--out = \"-\": results go to files (the table is on standard output); give a file name, "
        "or ./- for a file named \"-\"");
  Target t;
  t.file = path;
  struct stat ls {};
  if (::lstat(path.c_str(), &ls) != 0) {
    const int e = errno;
    if (e != ENOENT) throw UserError(path + ": cannot be written (" + why(e) + ")");
    const std::string dir = parent_of(path);
    struct stat ds {};
    if (::stat(dir.c_str(), &ds) != 0 || !S_ISDIR(ds.st_mode))
      throw UserError(path + ": the directory " + dir + " does not exist");
    return t;
  }
  t.st = ls;
  if (S_ISLNK(ls.st_mode)) {
    if (::stat(path.c_str(), &t.st) != 0) {
      const int e = errno;
      if (e == ENOENT)
        throw UserError(path + ": is a symbolic link to " + link_text(path) +
                        ", which does not exist; not writing through a dangling link (remove the link, or name "
                        "the file it should point to)");
      throw UserError(path + ": cannot be written (" + why(e) + ")");
    }
    if (S_ISREG(t.st.st_mode)) {
      char* real = ::realpath(path.c_str(), nullptr);
      if (!real) throw UserError(path + ": cannot resolve the symbolic link (" + why(errno) + ")");
      t.file = real;
      std::free(real);
    }
  }
  const mode_t m = t.st.st_mode;
  if (S_ISDIR(m)) throw UserError(path + ": is a directory");
  if (S_ISREG(m)) {
    if (!overwrite) throw UserError(path + ": exists already; pass --force to overwrite it, or choose another name");
    t.kind = Kind::regular;
    return t;
  }
  if (S_ISCHR(m) || S_ISFIFO(m)) {
    t.kind = Kind::write_through;
    return t;
  }
  const char* what = S_ISBLK(m) ? "a block device" : S_ISSOCK(m) ? "a socket" : "not a regular file";
  throw UserError(path + ": is " + what +
                  "; --out writes regular files, character devices (such as /dev/null) and FIFOs");
}

// Removes TARGET.vgroove-tmp.PID files in the target's directory whose process is gone.
void remove_stale_temporaries(const std::string& file) {
  const std::string prefix = name_of(temporary_name(file, 0));
  const std::string stem = prefix.substr(0, prefix.size() - 1);  // without the pid "0"
  const std::string dir = parent_of(file);
  DIR* d = ::opendir(dir.c_str());
  if (!d) return;
  while (const dirent* e = ::readdir(d)) {
    const std::string n = e->d_name;
    if (n.size() <= stem.size() || n.compare(0, stem.size(), stem) != 0) continue;
    const std::string digits = n.substr(stem.size());
    if (digits.size() > 18 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(digits);
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) ::unlink((dir + "/" + n).c_str());
  }
  ::closedir(d);
}

void write_all(int fd, const std::string& text, const std::string& path) {
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw UserError(path + ": writing failed (" + why(errno) + ")");
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

// Opens a new temporary file for `file`; a leftover of a dead process with our pid is replaced.
int open_temporary(const std::string& tmp) {
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0 && errno == EEXIST) {
    ::unlink(tmp.c_str());
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  }
  return fd;
}

// Refuses targets that are one of the inputs, or the file standard output or error goes to.
void check_not_an_input(const std::string& path, const Target& t, const std::vector<std::string>& inputs) {
  if (t.kind != Kind::regular) return;
  for (const std::string& in : inputs) {
    struct stat s {};
    if (::stat(in.c_str(), &s) == 0 && same_file(s, t.st))
      throw UserError(path + ": is the input file " + in + "; the output would replace it (choose another name)");
  }
  for (int fd : {STDOUT_FILENO, STDERR_FILENO}) {
    struct stat s {};
    if (::fstat(fd, &s) == 0 && S_ISREG(s.st_mode) && same_file(s, t.st))
      throw UserError(path + ": is the file standard " + std::string(fd == STDOUT_FILENO ? "output" : "error") +
                      " goes to; the report would replace it (choose another name)");
  }
}

}  // namespace

std::string temporary_name(const std::string& target, long pid) {
  std::string name = name_of(target).substr(0, 200);
  const std::string dir = std::filesystem::path(target).parent_path().string();
  return (dir.empty() ? std::string() : dir + "/") + name + ".vgroove-tmp." + std::to_string(pid);
}

void check_writable_target(const std::string& path, bool overwrite, const std::vector<std::string>& inputs) {
  const Target t = classify(path, overwrite);
  check_not_an_input(path, t, inputs);
  if (t.kind == Kind::write_through) {
    if (::access(path.c_str(), W_OK) != 0) throw UserError(path + ": cannot be written (" + why(errno) + ")");
    return;
  }
  // Create (and remove) the temporary file the write will use: the one reliable test that the
  // directory takes new files (permissions, read-only mounts, /proc, a full inode table).
  const std::string tmp = temporary_name(t.file, ::getpid());
  const int fd = open_temporary(tmp);
  if (fd < 0)
    throw UserError(path + ": cannot create a file in the directory " + parent_of(t.file) + " (" + why(errno) + ")");
  ::close(fd);
  ::unlink(tmp.c_str());
}

void write_file_atomically(const std::string& path, const std::string& text, bool overwrite) {
  const Target t = classify(path, overwrite);
  if (t.kind == Kind::write_through) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) throw UserError(path + ": cannot be opened for writing (" + why(errno) + ")");
    try {
      write_all(fd, text, path);
    } catch (...) {
      ::close(fd);
      throw;
    }
    if (::close(fd) != 0) throw UserError(path + ": writing failed (" + why(errno) + ")");
    return;
  }
  remove_stale_temporaries(t.file);
  const std::string tmp = temporary_name(t.file, ::getpid());
  const int fd = open_temporary(tmp);
  if (fd < 0)
    throw UserError(path + ": cannot create a file in the directory " + parent_of(t.file) + " (" + why(errno) + ")");
  auto fail = [&](const std::string& what, int e) {
    ::unlink(tmp.c_str());
    throw UserError(path + ": " + what + " (" + why(e) + ")");
  };
  // A replaced file keeps its permission bits (a private report stays private).
  if (t.kind == Kind::regular && ::fchmod(fd, t.st.st_mode & 07777) != 0) {
    const int e = errno;
    ::close(fd);
    fail("cannot set the permissions of the new file", e);
  }
  try {
    write_all(fd, text, path);
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  if (::fsync(fd) != 0 && errno != EINVAL) {
    const int e = errno;
    ::close(fd);
    fail("writing failed", e);
  }
  if (::close(fd) != 0) fail("writing failed", errno);
  if (overwrite) {
    if (std::rename(tmp.c_str(), t.file.c_str()) != 0) fail("cannot rename the finished file into place", errno);
    return;
  }
  // Without --force a file that appeared during the run is not replaced either.
  if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, t.file.c_str(), RENAME_NOREPLACE) == 0) return;
  const int e = errno;
  if (e == EEXIST) {
    ::unlink(tmp.c_str());
    throw UserError(path +
                    ": exists already (created during the run); pass --force to overwrite it, or choose "
                    "another name");
  }
  if (e != EINVAL && e != ENOSYS) fail("cannot rename the finished file into place", e);
  // A file system without RENAME_NOREPLACE: link(2) fails rather than replace; one without hard
  // links either takes a plain rename after a last look.
  if (::link(tmp.c_str(), t.file.c_str()) == 0) {
    ::unlink(tmp.c_str());
    return;
  }
  struct stat s {};
  if (errno == EEXIST || ::lstat(t.file.c_str(), &s) == 0) {
    ::unlink(tmp.c_str());
    throw UserError(path +
                    ": exists already (created during the run); pass --force to overwrite it, or choose "
                    "another name");
  }
  if (std::rename(tmp.c_str(), t.file.c_str()) != 0) fail("cannot rename the finished file into place", errno);
}

}  // namespace vgroove::support
