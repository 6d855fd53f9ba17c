// vgroove CLI: a build without MPI: one process.
#include "vgroove/app/mpi_world.h"

namespace vgroove::app {

namespace {
const World kOne{};
}

void world_init(int*, char***) {}
void world_finalize() {}
const World& world() { return kOne; }
bool built_with_mpi() { return false; }
std::vector<std::string> gather_text(const std::string& mine) { return {mine}; }
bool all_ok(bool ok, const std::string& error, std::string* first_error) {
  if (!ok && first_error) *first_error = error;
  return ok;
}

}  // namespace vgroove::app
