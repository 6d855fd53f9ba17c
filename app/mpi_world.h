// vgroove CLI: the processes of a run. Built with -DVGROOVE_MPI=ON and started by mpirun (or
// srun), the command line's work runs on every rank: each runs its share of the work items
// (support/work_plan.h, the same split as --shard R+1/K) and sends its results to rank 0, which
// merges them (as `vgroove merge` does) and alone prints and writes. Without MPI, or started
// without mpirun, there is one process and none of this costs anything.
#pragma once

#include <string>
#include <vector>

namespace vgroove::app {

struct World {
  int rank = 0;
  int size = 1;
  bool distributed() const { return size > 1; }
  bool root() const { return rank == 0; }
};

// MPI_Init when built with MPI and started by an MPI launcher (it sets OMPI_COMM_WORLD_SIZE,
// PMI_SIZE or PMIX_RANK); one process otherwise.
void world_init(int* argc, char*** argv);
void world_finalize();
const World& world();
// Whether this build has MPI at all.
bool built_with_mpi();

// Rank 0 receives every rank's text, in rank order; the other ranks an empty list.
std::vector<std::string> gather_text(const std::string& mine);
// True on every rank when `ok` is true on every rank. Otherwise false on every rank, and
// `first_error` holds the message of the lowest rank that failed.
bool all_ok(bool ok, const std::string& error, std::string* first_error);

}  // namespace vgroove::app
