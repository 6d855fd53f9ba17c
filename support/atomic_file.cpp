#include "vgroove/support/atomic_file.h"

#include "vgroove/support/user_error.h"

#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace vgroove::support {

void check_writable_target(const std::string& path, bool overwrite) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(path, ec) && !overwrite)
    throw UserError(path + ": exists already; pass --force to overwrite it, or choose another name");
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw UserError(path + ": the directory " + parent.string() + " does not exist");
}

void write_file_atomically(const std::string& path, const std::string& text, bool overwrite) {
  check_writable_target(path, overwrite);
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw UserError(path + ": cannot write (" + std::strerror(errno) + ")");
    out << text;
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw UserError(path + ": writing failed (" + std::strerror(errno) + ")");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    throw UserError(path + ": cannot rename the finished file into place (" + why + ")");
  }
}

}  // namespace vgroove::support
