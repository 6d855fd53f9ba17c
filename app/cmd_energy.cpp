#include "vgroove/app/cli_options.h"
#include "vgroove/app/commands.h"
#include "vgroove/support/seconds_since.h"
#include "vgroove/validation/ranges.h"

#include "vgroove/app/distributed.h"
#include "vgroove/app/mpi_world.h"

#include "vgroove/app/options.h"
#include "vgroove/app/outputs.h"
#include "vgroove/app/progress.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/npy.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/energy_export.h"
#include "vgroove/validation/energy_table.h"

#include <chrono>
#include <iostream>

namespace vgroove::app {

using namespace validation;

std::optional<support::Shard> shard_from(const std::string& text, const std::string& out) {
  if (text.empty()) return std::nullopt;
  const support::Shard s = support::parse_shard(text, "--shard");
  if (out.empty()) throw support::UserError("--shard needs --out (the partial report to write)");
  return s;
}

void write_partial(const std::string& out, const nlohmann::json& part, bool force) {
  support::write_file_atomically(out, support::json_text(part) + "\n", force);
  const nlohmann::json& h = part["partial"];
  std::cout << "partial report: " << out << " (shard " << h["shard"]["index"] << "/" << h["shard"]["count"] << ", "
            << h["items"].size() << " of " << h["job"]["items"] << " work items, " << part["units"].size() << " units, "
            << h["wall_s"].get<double>() << " s); merge the parts with `vgroove merge PART... --out R.json`\n";
}

std::vector<std::string> energy_npy_files(const EnergyGrid& g, const std::string& out, bool npy) {
  const std::size_t largest = g.cells() * (static_cast<std::size_t>(g.max_k) + 1);
  if (out.empty() || (!npy && largest <= kInlineArrayValues)) return {};
  std::string base = out;
  if (base.size() > 5 && base.ends_with(".json")) base.resize(base.size() - 5);
  EnergyTable empty;
  empty.grid = g;
  std::vector<std::string> files;
  for (const EnergyArray& a : energy_arrays(empty)) files.push_back(base + "." + a.name + ".npy");
  return files;
}

void write_energy_table(const EnergyTable& t, const std::string& out, bool npy, bool force) {
  print_energy_table(std::cout, t);
  if (out.empty()) return;
  const std::vector<std::string> files = energy_npy_files(t.grid, out, npy);
  const std::vector<EnergyArray> arrays = energy_arrays(t);
  for (std::size_t n = 0; n < files.size(); ++n)
    support::write_file_atomically(files[n], support::npy_bytes(arrays[n].values, arrays[n].shape), force);
  support::write_file_atomically(out, support::json_text(energy_table_json(t, files), 1) + "\n", force);
  std::cout << "table: " << out;
  if (!files.empty()) std::cout << " (arrays in " << files.size() << " .npy files beside it)";
  std::cout << "\n";
}

int cmd_energy(const EnergyArgs& a) {
  std::vector<std::string> runs;
  if (a.audit) runs.push_back("--audit");
  if (!a.export_base.empty()) runs.push_back("--export");
  if (a.lobe_shape) runs.push_back("--lobe-shape");
  if (!a.eta.empty()) runs.push_back("--eta");
  if (runs.size() >= 2) {
    std::string list;
    for (std::size_t n = 0; n < runs.size(); ++n) list += (n ? (n + 1 == runs.size() ? " and " : ", ") : "") + runs[n];
    const char* count[] = {"", "", "two", "three", "four"};
    throw support::UserError(list + " are " + count[runs.size()] + " runs: give one");
  }
  if (!a.eta.empty()) return cmd_energy_glass(a);
  if (a.sides_given) throw support::UserError("--side applies to the glass tables (--eta)");
  if (a.grooves_given) throw support::UserError("--grooves applies to the glass tables (--eta)");
  if (a.audit) return cmd_energy_audit(a);  // --reference heightfield: its third reference
  if (a.reference_given)
    throw support::UserError("--reference applies to the glass tables (--eta) and to --audit (heightfield)");
  if (a.lobe_shape) return cmd_energy_lobe_shape(a);
  if (!a.export_base.empty()) return cmd_energy_export(a);
  check_threads(a.threads, "--threads");
  EnergyGrid g;
  g.ndfs.clear(), g.dims.clear();
  for (const std::string& n : a.ndfs) {
    const auto k = ndf_from_name(n);
    if (!k) throw support::UserError("--ndf = \"" + n + "\" is not one of \"ggx\", \"beckmann\", \"phong\"");
    g.ndfs.push_back(*k);
  }
  for (const std::string& d : a.dims) {
    if (d != "flatland" && d != "3d")
      throw support::UserError("--dim = \"" + d + "\" is not one of \"flatland\", \"3d\"");
    g.dims.push_back(d == "flatland" ? SurfaceDim::flatland : SurfaceDim::three_d);
  }
  auto points = [](int n, const std::string& flag, int most, const std::string& why) {
    if (n < 1 || n > most)
      throw support::UserError(flag + " = " + std::to_string(n) + " is out of range [1, " + std::to_string(most) + "]" +
                               why);
    return midpoints(n);
  };
  g.mus = a.mu.empty()
              ? points(a.mu_points, "--mu-points", kMaxMuPoints,
                       " (the smallest midpoint 0.5/n stays >= cos 89.9 deg = " + support::number_text(kMinMu) + ")")
              : a.mu;
  g.alphas = a.alpha.empty() ? points(a.alpha_points, "--alpha-points", kMaxAlphaPoints,
                                      " (the smallest midpoint 0.5/n stays >= " + support::number_text(kMinAlpha) + ")")
                             : a.alpha;
  g.rays = a.rays;
  check_seed(a.seed, "--seed");
  g.seed = static_cast<std::uint64_t>(a.seed);
  g.max_k = a.max_k;
  check_energy_grid(g);
  const std::optional<support::Shard> shard = shard_from(a.shard, a.out);
  if (shard && world().distributed())
    throw support::UserError("--shard cannot be combined with mpirun (the ranks split the work among themselves)");
  if (!a.out.empty()) {
    support::check_writable_target(a.out, a.force);  // fail before the work, not after
    if (!shard)
      for (const std::string& f : energy_npy_files(g, a.out, a.npy)) support::check_writable_target(f, a.force);
  }
  if (a.dry_run) return 0;
  if (shard) {
    const auto part =
        run_job_part(energy_job(g), *shard, a.threads, terminal_progress("energy " + shard->text()), a.cancel);
    if (!part) return interrupted_no_report();
    write_partial(a.out, *part, a.force);
    return 0;
  }
  if (world().distributed()) {
    const auto t0 = std::chrono::steady_clock::now();
    int threads = 0;
    auto results = run_distributed(energy_job(g), a.threads, terminal_progress("energy"), a.cancel, &threads);
    if (!results) return 0;  // not rank 0: its results went there
    EnergyTable t = energy_table_from(g, std::move(*results));
    t.threads = threads;
    t.wall_s = support::seconds_since(t0);
    write_energy_table(t, a.out, a.npy, a.force);
    return 0;
  }
  const auto table = run_energy_table(g, a.threads, terminal_progress("energy"), a.cancel);
  if (!table) return interrupted_no_report();
  write_energy_table(*table, a.out, a.npy, a.force);
  return 0;
}

void add_energy_command(CLI::App& app, Commands& commands) {
  using validation::kMaxAlpha;
  using validation::kMaxAlphaPoints;
  using validation::kMaxEnergyK;
  using validation::kMaxEnergyRays;
  using validation::kMaxMuPoints;
  using validation::kMinAlpha;
  using validation::kMinMu;
  auto* energy = app.add_subcommand(
      "energy",
      "Exact energy tables: the directional albedo E(mu, alpha) of V-groove surfaces per bounce order k (F = 1; "
      "E_1 what single scattering keeps, the rest what it loses), traced with every ray in a groove of its own "
      "drawn from the NDF, with standard errors, beside the analytic model (quadrature) and Cook-Torrance.");
  EnergyArgs& ea = commands.add(energy, cmd_energy);
  ea.cancel = commands.context().cancel;
  add_list(energy, "--ndf", ea.ndfs, "NDFs, comma-separated: ggx, beckmann, phong");
  add_list(energy, "--dim", ea.dims, "dimensions, comma-separated: flatland, 3d");
  add_real(energy, "--mu", ea.mu,
           "mu = cos theta_i, comma-separated, each in " + support::interval_text(kMinMu, true, 1.0, true) +
               " (theta_i <= 89.9 deg; default: --mu-points)")
      ->delimiter(',');
  add_integer(energy, "--mu-points", ea.mu_points, "mu at the midpoints (i + 1/2)/n of (0, 1], n", 1, kMaxMuPoints,
              " (the smallest midpoint 0.5/n stays >= cos 89.9 deg)")
      ->capture_default_str();
  add_real(energy, "--alpha", ea.alpha,
           "roughness, comma-separated, each in " + support::interval_text(kMinAlpha, true, kMaxAlpha, true) +
               " (default: --alpha-points)")
      ->delimiter(',');
  add_integer(energy, "--alpha-points", ea.alpha_points, "alpha at the midpoints (j + 1/2)/n of (0, 1], n", 1,
              kMaxAlphaPoints, " (the smallest midpoint 0.5/n stays >= 0.01)")
      ->capture_default_str();
  add_integer(energy, "--rays", ea.rays, "rays per cell", 1, kMaxEnergyRays)->capture_default_str();
  add_seed(energy, ea.seed, "seed of the rays' streams")->capture_default_str();
  add_integer(energy, "--max-k", ea.max_k, "bounce orders tabulated one by one (a last row holds k > max-k)", 1,
              kMaxEnergyK)
      ->capture_default_str();
  add_threads(energy, ea.threads);
  add_text(energy, "--out", ea.out, "table JSON to write (refuses to overwrite without --force)");
  energy->add_flag("--npy", ea.npy,
                   "write the arrays as .npy files beside the JSON (OUT.E_sim.npy, ...); automatic above 65536 values");
  add_shard(energy, ea.shard, "`vgroove merge` joins them");
  energy->add_flag("--force", ea.force, "overwrite existing files");
  energy->add_flag("--audit", ea.audit,
                   "the energy audit over the grid (GGX and Beckmann; --rays: walk paths per cell): compensation "
                   "formulas against the V-groove model and the Smith random walk (its report's /spec is a suite for "
                   "`vgroove validate`, which shards and runs under mpirun)");
  energy->add_flag(
      "--lobe-shape", ea.lobe_shape,
      "the compensated lobes' shape beyond energy (3D, F = 1; one --ndf, ggx or beckmann; --alpha, default "
      "0.5,1; --mu = cos theta_i, default theta_i 0,40,70 deg; --rays per theta_i): f_ss alone, Kulla-Conty "
      "and the view-scaled factor (Turquin, Filament, Bevy, Cycles) against the traced V-groove surface "
      "and the Smith random walk, by the Fig. 11 metric; exit 1 when a control fails");
  add_real(energy, "--eta", ea.eta,
           "rough glass tables: eta = n2 / n1 (below the surface over above it), comma-separated, each in " +
               support::interval_text(validation::kMinGlassEta, true, validation::kMaxGlassEta, true) +
               ", not 1: exact E_R and E_T per k of V-groove surfaces between two dielectrics (--ndf ggx, beckmann; "
               "--dim; --side), with the reciprocity of their hemispherical averages")
      ->delimiter(',');
  auto* sides = add_list(energy, "--side", ea.sides,
                         "--eta's light: from above (medium 1), below (medium 2) or both, comma-separated")
                    ->capture_default_str();
  auto* grooves =
      add_integer(energy, "--grooves", ea.grooves, "--eta's grooves per surface", 1, validation::kMaxGlassGrooves)
          ->capture_default_str();
  auto* reference = add_text(energy, "--reference", ea.reference,
                             "--eta's tables from: vgroove (the traced V-groove surfaces) or smith_walk (Heitz et al. "
                             "2016's dielectric random walk; --grooves not used); with --audit, heightfield adds the "
                             "random heightfields as a third reference (4 fields of 256^2 cells, --rays / 4 rays per "
                             "field and cell)")
                        ->capture_default_str();
  energy->callback([&ea, sides, grooves, reference]() {
    ea.sides_given = sides->count() > 0;
    ea.grooves_given = grooves->count() > 0;
    ea.reference_given = reference->count() > 0;
  });
  add_text(energy, "--export", ea.export_base,
           "write tables engines can load to BASE.json, .npz, .h, .png, .exr (see --formats): E_ss, E_avg, the DFG "
           "scale and bias, and with --ms-reference the exact multiple-scattering albedo per F0");
  add_text(energy, "--layout", ea.layout, "--export's layout: cycles (32 texel ends, Cycles' table_ggx_E) or centres")
      ->capture_default_str();
  add_integer(energy, "--size", ea.size, "--export's texels per axis", 2, validation::kMaxExportSize)
      ->capture_default_str();
  add_text(energy, "--masking", ea.masking, "--export's G2 without --ms-reference: smith, smith_separable, vcavity")
      ->capture_default_str();
  add_text(energy, "--ms-reference", ea.ms_reference,
           "--export's multiple scattering: none, vgroove (V-cavity single scattering), smith_walk (Smith's; "
           "--rays paths per texel)")
      ->capture_default_str();
  add_real(energy, "--ms-F0", ea.ms_F0, "--export's Schlick F0 axis, comma-separated, each in [0, 1]")->delimiter(',');
  add_list(energy, "--formats", ea.formats, "--export's files, comma-separated: json, npz, h, png, exr")
      ->capture_default_str();
}

}  // namespace vgroove::app
