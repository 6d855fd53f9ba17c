#include "vgroove/app/commands.h"

#include <iostream>
#include "vgroove/app/progress.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/validation/validate.h"

namespace vgroove::app {

int cmd_validate(const ValidateArgs& a) {
  validation::ValidateOptions o;
  o.suite = a.suite;
  if (a.rays != kUnset) o.rays = a.rays;
  o.threads = a.threads;
  if (!a.sampling.empty()) o.sampling = a.sampling;
  if (!a.eq6_form.empty()) o.eq6_form = a.eq6_form;
  if (a.seed != kUnsetSeed) o.seed = a.seed;
  const validation::ValidationPlan plan = validation::plan_validation(o);
  if (!a.out.empty()) support::check_writable_target(a.out, a.force);  // fail before the work, not after
  if (a.dry_run) return 0;
  const validation::ValidationResult res = validation::run_validation(plan, terminal_progress, a.cancel);
  if (res.interrupted) return interrupted_no_report();
  std::cout << res.table;
  if (!a.out.empty()) {
    support::write_file_atomically(a.out, res.report.dump(1) + "\n", a.force);
    std::cout << "report: " << a.out << "\n";
  }
  return res.pass ? 0 : 1;
}

}  // namespace vgroove::app
