// `vgroove energy --audit` and `vgroove energy --export` (validation/energy_audit.h,
// validation/energy_export.h).
#include "vgroove/analytic/masking_kind.h"
#include "vgroove/app/commands.h"

#include "vgroove/app/energy_images.h"
#include "vgroove/app/mpi_world.h"
#include "vgroove/app/options.h"
#include "vgroove/app/progress.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/format.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/energy_audit.h"
#include "vgroove/validation/energy_export.h"
#include "vgroove/validation/energy_table.h"
#include "vgroove/validation/suite_kind.h"

#include <iostream>

namespace vgroove::app {

using namespace validation;

namespace {

const std::vector<std::string> kDefaultNdfs{"ggx", "beckmann", "phong"};

std::vector<double> grid_values(const std::vector<double>& given, int points, const std::string& flag, int most) {
  if (!given.empty()) return given;
  if (points < 1 || points > most)
    throw support::UserError(flag + " = " + std::to_string(points) + " is out of range [1, " + std::to_string(most) +
                             "]");
  return midpoints(points);
}

// The audit's NDFs: GGX and Beckmann (the walk needs Smith's Lambda); the energy table's default list
// without Phong.
std::vector<std::string> audit_ndfs(const std::vector<std::string>& given) {
  if (given == kDefaultNdfs) return {"ggx", "beckmann"};
  for (const std::string& n : given)
    if (n != "ggx" && n != "beckmann")
      throw support::UserError("--ndf = \"" + n +
                               "\" is not one of \"ggx\", \"beckmann\" (the audit's Smith walk needs Lambda in "
                               "closed form)");
  return given;
}

}  // namespace

int cmd_energy_audit(const EnergyArgs& a) {
  check_threads(a.threads, "--threads");
  check_seed(a.seed, "--seed");
  if (!a.shard.empty() || world().distributed())
    throw support::UserError(
        "--audit runs in one process; to split it, run its suite with `vgroove validate SUITE --shard I/N` or under "
        "mpirun (the report of --audit --out holds the suite under /spec; data/suites/energy_audit.json is one)");
  if (a.max_k < 1 || a.max_k > kMaxAuditK)
    throw support::UserError("--max-k = " + std::to_string(a.max_k) + " is out of range [1, " +
                             std::to_string(kMaxAuditK) + "] with --audit");
  if (a.reference_given && a.reference != "heightfield")
    throw support::UserError("--reference = \"" + a.reference +
                             "\" is not \"heightfield\" with --audit (the V-groove model and the Smith walk are always "
                             "audited; heightfield adds the random heightfields)");
  // In this order, so that the first bad flag is the one named.
  const std::vector<std::string> ndfs = audit_ndfs(a.ndfs);
  const std::vector<double> alphas = grid_values(a.alpha, a.alpha_points, "--alpha-points", kMaxAlphaPoints);
  const std::vector<double> mus = grid_values(a.mu, a.mu_points, "--mu-points", kMaxMuPoints);
  const nlohmann::json suite =
      energy_audit_command_suite(ndfs, alphas, mus, a.rays, a.seed, a.max_k, a.reference_given);
  const std::string where = "vgroove energy --audit";
  // The grid's own messages (--mu, --alpha, --rays) first, then the suite's.
  if (a.rays < 1 || a.rays > kMaxAuditPaths)
    throw support::UserError("--rays = " + std::to_string(a.rays) + " is out of range [1, " +
                             std::to_string(kMaxAuditPaths) + "] (walk paths per cell with --audit)");
  const std::unique_ptr<PlannedSuite> plan = find_kind(suite).plan(suite, where, {});
  if (!a.out.empty()) support::check_writable_target(a.out, a.force);
  if (a.dry_run) return 0;
  const nlohmann::json descriptor = {{"command", "energy --audit"}, {"kind", "energy_audit"}, {"input", suite}};
  const auto job = plan->job(descriptor, a.cancel);
  const auto r = job->run(a.threads, terminal_progress("energy audit"), a.cancel, !a.out.empty());
  if (!r) return interrupted_no_report();
  std::cout << r->table;
  if (!a.out.empty()) {
    support::write_file_atomically(a.out, r->report.dump(1) + "\n", a.force);
    std::cout << "report: " << support::printable(a.out) << "\n";
  }
  return r->pass ? 0 : 1;
}

namespace {

struct ExportFile {
  std::string path;
  std::string bytes;
};

std::string slice_name(const std::string& table, double F0) { return table + ".F0_" + support::number_text(F0); }

}  // namespace

int cmd_energy_export(const EnergyArgs& a) {
  check_threads(a.threads, "--threads");
  check_seed(a.seed, "--seed");
  if (!a.shard.empty() || world().distributed())
    throw support::UserError("--export runs in one process (--shard and mpirun apply to the energy tables and audits)");
  EnergyExportOptions o;
  const std::vector<std::string> ndfs = a.ndfs == kDefaultNdfs ? std::vector<std::string>{"ggx"} : a.ndfs;
  if (ndfs.size() != 1)
    throw support::UserError("--ndf has " + std::to_string(ndfs.size()) +
                             " values; --export takes one (ggx, beckmann)");
  const auto k = ndf_from_name(ndfs.front());
  if (!k) throw support::UserError("--ndf = \"" + ndfs.front() + "\" is not one of \"ggx\", \"beckmann\"");
  o.model.ndf = *k;
  const auto masking = analytic::masking_from_flag(a.masking);
  if (!masking)
    throw support::UserError("--masking = \"" + a.masking +
                             "\" is not one of \"smith\", \"smith_separable\", \"vcavity\"");
  o.model.masking = *masking;
  o.layout = a.layout;
  o.size = a.size;
  o.ms_reference = a.ms_reference;
  if (!a.ms_F0.empty()) o.ms_F0 = a.ms_F0;
  o.walk_paths = a.rays;
  o.seed = static_cast<std::uint64_t>(a.seed);
  o.threads = a.threads;
  check_energy_export(o);
  for (const std::string& f : a.formats)
    if (f != "json" && f != "npz" && f != "h" && f != "png" && f != "exr")
      throw support::UserError("--formats = \"" + f + "\" is not one of \"json\", \"npz\", \"h\", \"png\", \"exr\"");
  auto wants = [&](const std::string& f) {
    return std::find(a.formats.begin(), a.formats.end(), f) != a.formats.end();
  };
  // Every file it will write, checked before the work (none is left half-written: each is written
  // whole from memory, atomically).
  const std::string& base = a.export_base;
  const bool ms = o.ms_reference != "none";
  std::vector<std::string> pngs = {"E_ss", "E_avg", "dfg_scale", "dfg_bias"};
  if (ms)
    for (double F0 : o.ms_F0) pngs.push_back(slice_name("E_ms", F0)), pngs.push_back(slice_name("compensation", F0));
  std::vector<std::string> targets;
  if (wants("json")) targets.push_back(base + ".json");
  if (wants("npz")) targets.push_back(base + ".npz");
  if (wants("h")) targets.push_back(base + ".h");
  if (wants("png"))
    for (const std::string& p : pngs) targets.push_back(base + "." + p + ".png");
  if (wants("exr")) targets.push_back(base + ".exr");
  for (const std::string& t : targets) support::check_writable_target(t, a.force);
  if (a.dry_run) return 0;
  const auto e = energy_export(o, terminal_progress("energy export"), a.cancel);
  if (!e) return interrupted_no_report();
  // Encode everything before writing anything.
  std::vector<ExportFile> files;
  if (wants("json")) files.push_back({base + ".json", export_json_text(*e)});
  if (wants("npz")) files.push_back({base + ".npz", export_npz_bytes(*e)});
  if (wants("h")) files.push_back({base + ".h", export_header_text(*e, c_identifier(base))});
  const std::string meta = e->metadata.dump(1);
  auto array = [&](const std::string& name) -> const ExportArray& {
    for (const ExportArray& x : e->arrays)
      if (x.name == name) return x;
    throw std::logic_error("no array " + name);
  };
  const ExportArray& E = array("E_ss");
  const int rows = static_cast<int>(E.shape[0]), cols = static_cast<int>(E.shape[1]);
  const std::size_t texels = static_cast<std::size_t>(rows) * cols;
  auto slice = [&](const ExportArray& x, std::size_t f) {
    return std::vector<double>(x.values.begin() + static_cast<std::ptrdiff_t>(f * texels),
                               x.values.begin() + static_cast<std::ptrdiff_t>((f + 1) * texels));
  };
  if (wants("png")) {
    for (const char* n : {"E_ss", "dfg_scale", "dfg_bias"})
      files.push_back({base + "." + n + ".png", png16_bytes(array(n).values, rows, cols, 1.0, meta)});
    const ExportArray& avg = array("E_avg");
    files.push_back({base + ".E_avg.png", png16_bytes(avg.values, 1, static_cast<int>(avg.values.size()), 1.0, meta)});
    if (ms)
      for (std::size_t f = 0; f < o.ms_F0.size(); ++f) {
        files.push_back({base + "." + slice_name("E_ms", o.ms_F0[f]) + ".png",
                         png16_bytes(slice(array("E_ms"), f), rows, cols, 1.0, meta)});
        files.push_back({base + "." + slice_name("compensation", o.ms_F0[f]) + ".png",
                         png16_bytes(slice(array("compensation"), f), rows, cols, 4.0, meta)});
      }
  }
  if (wants("exr")) {
    std::vector<ExrChannel> ch;
    for (const char* n : {"E_ss", "dfg_scale", "dfg_bias"}) ch.push_back({n, array(n).values});
    if (ms)
      for (std::size_t f = 0; f < o.ms_F0.size(); ++f) {
        ch.push_back({slice_name("E_ms", o.ms_F0[f]), slice(array("E_ms"), f)});
        ch.push_back({slice_name("compensation", o.ms_F0[f]), slice(array("compensation"), f)});
      }
    nlohmann::json m = e->metadata;
    m["E_avg"] = array("E_avg").values;
    files.push_back({base + ".exr", exr_bytes(ch, rows, cols, m.dump(1))});
  }
  for (const ExportFile& f : files) support::write_file_atomically(f.path, f.bytes, a.force);
  std::cout << "energy export: " << ndf_name(o.model.ndf) << " " << e->metadata["model"]["masking"].get<std::string>()
            << ", layout " << o.layout << " " << rows << " x " << cols << ", multiple scattering " << o.ms_reference
            << ", largest quadrature bound " << e->metadata["quadrature"]["largest_bound"].dump() << ", wall "
            << support::format("%.2f", e->wall_s) << " s\n";
  for (const ExportFile& f : files) std::cout << "  " << support::printable(f.path) << "\n";
  return 0;
}

}  // namespace vgroove::app
