// `vgroove energy --lobe-shape` (validation/energy_lobe_shape.h): the compensated lobes' shape
// against the traced V-groove surface and the Smith walk, a table and a JSON report.
#include "vgroove/app/commands.h"

#include "vgroove/app/mpi_world.h"
#include "vgroove/app/options.h"
#include "vgroove/app/progress.h"
#include "vgroove/common/angles.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/format.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/energy_lobe_shape.h"
#include "vgroove/validation/ranges.h"

#include <cmath>
#include <iostream>

namespace vgroove::app {

using namespace validation;

int cmd_energy_lobe_shape(const EnergyArgs& a) {
  check_threads(a.threads, "--threads");
  check_seed(a.seed, "--seed");
  if (!a.shard.empty() || world().distributed())
    throw support::UserError(
        "--lobe-shape runs in one process (--shard and mpirun apply to the energy tables and "
        "audits)");
  if (a.dims != EnergyArgs{}.dims && a.dims != std::vector<std::string>{"3d"})
    throw support::UserError("--dim: --lobe-shape is 3D (the compensation formulas are 3D BRDFs)");
  LobeShapeOptions o;
  const std::vector<std::string> ndfs = a.ndfs == EnergyArgs{}.ndfs ? std::vector<std::string>{"ggx"} : a.ndfs;
  if (ndfs.size() != 1 || (ndfs.front() != "ggx" && ndfs.front() != "beckmann"))
    throw support::UserError("--ndf: --lobe-shape takes one of \"ggx\", \"beckmann\" (the Smith walk needs Lambda)");
  o.ndf = *ndf_from_name(ndfs.front());
  for (double alpha : a.alpha)
    if (!(alpha >= kMinAlpha && alpha <= kMaxAlpha))
      throw support::UserError("--alpha = " + support::number_text(alpha) + " is out of range " +
                               support::interval_text(kMinAlpha, true, kMaxAlpha, true));
  if (!a.alpha.empty()) o.alpha = a.alpha;
  if (!a.mu.empty()) {
    o.theta_i_deg.clear();
    for (double mu : a.mu) {
      if (!(mu >= kMinMu && mu <= 1.0))
        throw support::UserError("--mu = " + support::number_text(mu) + " is out of range " +
                                 support::interval_text(kMinMu, true, 1.0, true));
      o.theta_i_deg.push_back(std::acos(mu) * kDegPerRad);
    }
  }
  if (a.rays < 1 || a.rays > kMaxRays)
    throw support::UserError("--rays = " + std::to_string(a.rays) + " is out of range [1, " + std::to_string(kMaxRays) +
                             "] (rays and walks per theta_i with --lobe-shape)");
  o.rays = static_cast<long>(a.rays);
  o.seed = static_cast<std::uint64_t>(a.seed);
  o.threads = a.threads;
  o.cancel = a.cancel;
  check_lobe_shape_options(o);
  if (!a.out.empty()) support::check_writable_target(a.out, a.force);
  if (a.dry_run) return 0;
  const LobeShapeResult r = audit_lobe_shapes(o);
  if (r.interrupted) return interrupted_no_report();
  print_lobe_shapes(std::cout, r);
  if (!a.out.empty()) {
    support::write_file_atomically(a.out, r.to_json().dump(1) + "\n", a.force);
    std::cout << "report: " << support::printable(a.out) << "\n";
  }
  return r.controls_pass ? 0 : 1;
}

}  // namespace vgroove::app
