#include "vgroove/app/commands.h"

#include "vgroove/app/options.h"
#include "vgroove/scene/simulate.h"
#include "vgroove/support/atomic_file.h"

#include <iostream>

namespace vgroove::app {

using namespace scene;

int cmd_simulate(const SimulateArgs& a) {
  check_threads(a.threads, "--threads");
  const Scene scene = load_scene(a.scene);
  if (!a.out.empty()) support::check_writable_target(a.out, a.force);  // fail before the work, not after
  if (a.dry_run) return 0;
  const SimulationResult r = simulate(scene, a.threads, a.cancel);
  if (r.interrupted) {
    std::cerr << "vgroove: interrupted; no result written\n";
    return kExitInterrupted;
  }
  print_result_table(std::cout, scene, r);
  if (!a.out.empty()) {
    support::write_file_atomically(a.out, result_json(scene, r).dump(1) + "\n", a.force);
    std::cout << "result: " << a.out << "\n";
  }
  return 0;
}

}  // namespace vgroove::app
