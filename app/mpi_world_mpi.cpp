// vgroove CLI: a build with MPI (-DVGROOVE_MPI=ON): the ranks of MPI_COMM_WORLD.
#include "vgroove/app/mpi_world.h"

#include <mpi.h>

#include <cstdlib>

namespace vgroove::app {

namespace {
World the_world;
bool initialized = false;

bool started_by_launcher() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v)) return true;
  return false;
}
}  // namespace

void world_init(int* argc, char*** argv) {
  if (!started_by_launcher()) return;
  MPI_Init(argc, argv);
  initialized = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &the_world.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &the_world.size);
}

void world_finalize() {
  if (initialized) MPI_Finalize();
  initialized = false;
}

const World& world() { return the_world; }
bool built_with_mpi() { return true; }

std::vector<std::string> gather_text(const std::string& mine) {
  if (!the_world.distributed()) return {mine};
  // Sizes first (texts may pass 2 GiB in total: each is sent on its own, in pieces).
  const long long n = static_cast<long long>(mine.size());
  std::vector<long long> sizes(static_cast<std::size_t>(the_world.size));
  MPI_Gather(&n, 1, MPI_LONG_LONG, sizes.data(), 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  constexpr long long kPiece = 1LL << 30;
  if (!the_world.root()) {
    for (long long at = 0; at < n; at += kPiece)
      MPI_Send(mine.data() + at, static_cast<int>(std::min(kPiece, n - at)), MPI_CHAR, 0, 0, MPI_COMM_WORLD);
    return {};
  }
  std::vector<std::string> all(static_cast<std::size_t>(the_world.size));
  all[0] = mine;
  for (int r = 1; r < the_world.size; ++r) {
    std::string& t = all[static_cast<std::size_t>(r)];
    t.resize(static_cast<std::size_t>(sizes[static_cast<std::size_t>(r)]));
    for (long long at = 0; at < sizes[static_cast<std::size_t>(r)]; at += kPiece)
      MPI_Recv(t.data() + at, static_cast<int>(std::min(kPiece, sizes[static_cast<std::size_t>(r)] - at)), MPI_CHAR, r,
               0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
  return all;
}

bool all_ok(bool ok, const std::string& error, std::string* first_error) {
  if (!the_world.distributed()) {
    if (!ok && first_error) *first_error = error;
    return ok;
  }
  // The lowest failing rank (size when none), then its message from it to everyone.
  const int mine = ok ? the_world.size : the_world.rank;
  int lowest = the_world.size;
  MPI_Allreduce(&mine, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (lowest == the_world.size) return true;
  int len = the_world.rank == lowest ? static_cast<int>(error.size()) : 0;
  MPI_Bcast(&len, 1, MPI_INT, lowest, MPI_COMM_WORLD);
  std::string text = the_world.rank == lowest ? error : std::string(static_cast<std::size_t>(len), ' ');
  MPI_Bcast(text.data(), len, MPI_CHAR, lowest, MPI_COMM_WORLD);
  if (first_error) *first_error = text;
  return false;
}

}  // namespace vgroove::app
