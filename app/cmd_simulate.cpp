#include "vgroove/app/commands.h"
#include "vgroove/support/printable.h"

#include "vgroove/app/options.h"
#include "vgroove/scene/simulate.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/memory.h"

#include <iostream>

namespace vgroove::app {

using namespace scene;

int cmd_simulate(const SimulateArgs& a) {
  check_threads(a.threads);
  const Scene scene = load_scene(a.scene);
  support::check_memory(simulate_memory_bytes(scene, a.threads, !a.out.empty()), a.scene + ": the run",
                        std::to_string(scene.light.theta_i.size()) + " incident angles x " +
                            std::to_string(scene.channels.size()) + " channels, " +
                            std::to_string(scene.record.theta_o_bins * (scene.record.histogram_max_k + 2)) +
                            " histogram cells" +
                            (scene.geometry.kind == GeometryKind::microsurface
                                 ? ", " + std::to_string(scene.geometry.grooves) + " grooves"
                                 : std::string()));
  if (!a.out.empty()) support::check_writable_target(a.out, a.force, {a.scene});  // fail before the work, not after
  if (a.dry_run) return 0;
  const SimulationResult r = simulate(scene, a.threads, a.cancel);
  if (r.interrupted) {
    std::cerr << "vgroove: interrupted; no result written\n";
    return kExitInterrupted;
  }
  print_result_table(std::cout, scene, r);
  if (!a.out.empty()) {
    support::write_file_atomically(a.out, result_json(scene, r).dump(1) + "\n", a.force);
    std::cout << "result: " << support::printable(a.out) << "\n";
  }
  return 0;
}

}  // namespace vgroove::app
