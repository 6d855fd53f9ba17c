// `vgroove energy --eta` (validation/glass_energy.h): exact E_R and E_T of rough glass, a table and
// a JSON file.
#include "vgroove/app/commands.h"

#include "vgroove/app/distributed.h"
#include "vgroove/app/mpi_world.h"
#include "vgroove/app/options.h"
#include "vgroove/app/outputs.h"
#include "vgroove/app/progress.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/energy_table.h"
#include "vgroove/validation/glass_energy.h"

#include <chrono>
#include <iostream>

namespace vgroove::app {

using namespace validation;

int cmd_energy_glass(const EnergyArgs& a) {
  check_threads(a.threads, "--threads");
  check_seed(a.seed, "--seed");
  if (a.npy) throw support::UserError("--npy applies to the conductor tables (--eta writes its arrays in the JSON)");
  GlassGrid g;
  // Without --ndf: GGX (the default list's Phong has no glass tables).
  set_glass_axes(g, a.ndfs == EnergyArgs{}.ndfs ? std::vector<std::string>{"ggx"} : a.ndfs, a.dims, a.sides);
  g.etas = a.eta;
  g.mus = a.mu.empty() ? midpoints(a.mu_points) : a.mu;
  if (a.mu.empty() && (a.mu_points < 1 || a.mu_points > kMaxMuPoints))
    throw support::UserError("--mu-points = " + std::to_string(a.mu_points) + " is out of range [1, " +
                             std::to_string(kMaxMuPoints) + "]");
  if (a.alpha.empty() && (a.alpha_points < 1 || a.alpha_points > kMaxAlphaPoints))
    throw support::UserError("--alpha-points = " + std::to_string(a.alpha_points) + " is out of range [1, " +
                             std::to_string(kMaxAlphaPoints) + "]");
  g.alphas = a.alpha.empty() ? midpoints(a.alpha_points) : a.alpha;
  g.rays = a.rays;
  g.seed = static_cast<std::uint64_t>(a.seed);
  g.max_k = a.max_k;
  g.grooves = a.grooves;
  g.reference = glass_reference_from(a.reference);
  check_glass_grid(g);
  const std::optional<support::Shard> shard = shard_from(a.shard, a.out);
  if (shard && world().distributed())
    throw support::UserError("--shard cannot be combined with mpirun (the ranks split the work among themselves)");
  if (!a.out.empty()) support::check_writable_target(a.out, a.force);
  if (a.dry_run) return 0;
  if (shard) {
    const auto part = run_job_part(glass_job(g, a.cancel), *shard, a.threads,
                                   terminal_progress("energy --eta " + shard->text()), a.cancel);
    if (!part) return interrupted_no_report();
    write_partial(a.out, *part, a.force);
    return 0;
  }
  if (world().distributed()) {
    const auto t0 = std::chrono::steady_clock::now();
    int threads = 0;
    auto results =
        run_distributed(glass_job(g, a.cancel), a.threads, terminal_progress("energy --eta"), a.cancel, &threads);
    if (!results) return 0;  // not rank 0: its results went there
    GlassTable t = glass_table_from(g, std::move(*results));
    t.threads = threads;
    t.wall_s = support::seconds_since(t0);
    write_glass_table(t, a.out, a.force);
    return 0;
  }
  const auto t = run_glass_table(g, a.threads, terminal_progress("energy --eta"), a.cancel);
  if (!t) return interrupted_no_report();
  write_glass_table(*t, a.out, a.force);
  return 0;
}

void write_glass_table(const validation::GlassTable& t, const std::string& out, bool force) {
  const std::vector<validation::GlassCompensationRow> audit = validation::glass_compensation_audit(t);
  print_glass_table(std::cout, t, audit);
  if (out.empty()) return;
  support::write_file_atomically(out, support::json_text(glass_table_json(t, audit), 1) + "\n", force);
  std::cout << "table: " << support::printable(out) << "\n";
}

}  // namespace vgroove::app
