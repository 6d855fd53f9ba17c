#include "vgroove/support/std_streams.h"

#include <fcntl.h>
#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <streambuf>

namespace vgroove::support {

namespace {

// std::cout's buffer, passing everything to the one it replaces and keeping the errno of the first
// write that failed: a write that fails before the final flush (output larger than C's buffer)
// leaves the stream bad, and the flush then writes nothing and sets no errno.
class FirstErrorBuf : public std::streambuf {
 public:
  explicit FirstErrorBuf(std::streambuf* inner) : inner_(inner) {}
  int first_errno() const { return first_errno_; }

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    errno = 0;
    const int_type r = inner_->sputc(traits_type::to_char_type(c));
    if (traits_type::eq_int_type(r, traits_type::eof())) note();
    return r;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    errno = 0;
    const std::streamsize r = inner_->sputn(s, n);
    if (r < n) note();
    return r;
  }
  int sync() override {
    errno = 0;
    const int r = inner_->pubsync();
    if (r != 0) note();
    return r;
  }

 private:
  void note() {
    if (first_errno_ == 0) first_errno_ = errno;
  }
  std::streambuf* inner_;
  int first_errno_ = 0;
};

// Never destroyed: std::cout is flushed after every static object's destructor has run (at the end
// of std::ios_base::Init), and its buffer must still be there then.
FirstErrorBuf& cout_buf() {
  static FirstErrorBuf* const buf = new FirstErrorBuf(std::cout.rdbuf());
  return *buf;
}

}  // namespace

void guard_standard_descriptors() {
  std::cout.rdbuf(&cout_buf());
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    // open() returns the lowest free descriptor: this one. Input is opened write-only and the
    // outputs read-only, so every use of the closed stream still fails.
    const int got = ::open("/dev/null", fd == 0 ? O_WRONLY : O_RDONLY);
    if (got >= 0 && got != fd) ::close(got);
  }
}

std::string flush_standard_output() {
  errno = 0;
  std::cout.flush();
  const bool cout_bad = !std::cout.good();
  const int flush = std::fflush(stdout);
  const int e = errno != 0 ? errno : cout_buf().first_errno();
  if (flush == 0 && !std::ferror(stdout) && !cout_bad) return "";
  std::clearerr(stdout);
  std::cout.clear();
  return std::string("standard output: write failed") + (e ? std::string(" (") + std::strerror(e) + ")" : "");
}

}  // namespace vgroove::support
