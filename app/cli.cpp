#include "vgroove/app/cli.h"

#include "vgroove/analytic/sampling_nonsymmetric.h"
#include "vgroove/app/commands.h"
#include "vgroove/app/distributed.h"
#include "vgroove/app/mpi_world.h"
#include "vgroove/app/options.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/std_streams.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/energy_export.h"
#include "vgroove/validation/energy_table.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <iostream>
#include <iterator>
#include <limits>
#include <new>
#include <string>
#include <vector>

namespace vgroove::app {

namespace {

using namespace validation;

// Validators run on the option's text before CLI11 converts it: numbers are read strictly and
// in range (options.h), text options may not be empty. They throw a UserError naming the option.
CLI::Validator strict_integer(const std::string& name, long long lo, long long hi, const std::string& note = "") {
  return CLI::Validator([=](std::string& s) { return s = integer_text(s, name, lo, hi, note), std::string(); }, "", "");
}
CLI::Validator strict_real(const std::string& name) {
  return CLI::Validator([=](std::string& s) { return s = real_text(s, name), std::string(); }, "", "");
}
CLI::Validator non_empty(const std::string& name) {
  return CLI::Validator(
      [=](std::string& s) {
        if (s.empty()) throw support::UserError(name + " = \"\" is empty");
        return std::string();
      },
      "", "");
}
std::string range_text(long long lo, long long hi) {
  std::string s(1, '[');  // appended piecewise: GCC 12 warns on "[" + std::string (bug 105651)
  s += std::to_string(lo);
  s += ", ";
  s += std::to_string(hi);
  return s + "]";
}
template <class T>
CLI::Option* add_integer(CLI::App* app, const std::string& name, T& v, const std::string& help, long long lo,
                         long long hi, const std::string& note = "") {
  return app->add_option(name, v, help + ", " + range_text(lo, hi))->transform(strict_integer(name, lo, hi, note));
}
template <class T>
CLI::Option* add_real(CLI::App* app, const std::string& name, T& v, const std::string& help) {
  return app->add_option(name, v, help)->transform(strict_real(name));
}
template <class T>
CLI::Option* add_text(CLI::App* app, const std::string& name, T& v, const std::string& help) {
  return app->add_option(name, v, help)->check(non_empty(name));
}
// Comma-separated values in one option (--ndf ggx,phong), each non-empty.
template <class T>
CLI::Option* add_list(CLI::App* app, const std::string& name, std::vector<T>& v, const std::string& help) {
  return add_text(app, name, v, help)->delimiter(',')->capture_default_str();
}
CLI::Option* add_threads(CLI::App* app, int& v) {
  return add_integer(app, "--threads", v, "worker threads (0: all cores); results do not depend on it", 0, kMaxThreads,
                     " (0: all cores)")
      ->capture_default_str();
}
CLI::Option* add_seed(CLI::App* app, long long& v, const std::string& help) {
  return add_integer(app, "--seed", v, help, 0, kMaxSeed);
}
// --theta-v-deg for a symmetric groove, or --theta-l-deg with --theta-r-deg for a nonsymmetric one.
void add_groove_options(CLI::App* app, GrooveArgs& g) {
  auto* v =
      add_real(app, "--theta-v-deg", g.theta_v_deg,
               "symmetric groove: aperture theta_v in degrees, [" + support::number_text(kMinApertureDeg) + ", 180]")
          ->capture_default_str();
  auto* l = add_real(app, "--theta-l-deg", g.theta_l_deg,
                     "nonsymmetric groove: angle of the left facet's normal from n, [-90, 0] (Lee et al. "
                     "2018, Fig. 5; counter-clockwise positive, so the left facet's normal leans right and "
                     "theta_l <= 0)");
  auto* r = add_real(app, "--theta-r-deg", g.theta_r_deg,
                     "nonsymmetric groove: angle of the right facet's normal, [0, 90]; aperture "
                     "theta_v = 180 + theta_l - theta_r >= " +
                         support::number_text(kMinApertureDeg) + "; a symmetric groove is theta_l = -theta_r");
  l->needs(r);
  r->needs(l);
  app->callback([&g, v, l]() {
    g.nonsymmetric = l->count() > 0;
    g.theta_v_given = v->count() > 0;
  });
}

// Every rank of an MPI run sees the same input errors: rank 0 alone prints them.
void print_error(const std::string& what) {
  if (world().root()) std::cerr << "vgroove: error: " << support::printable(what) << "\n";
}

int run_command(int argc, const char* const* argv, const CliContext& ctx) {
  CLI::App app{
      "vgroove: traces light exactly through 2D V-grooves and checks the kaleidoscopic model of\n"
      "Lee et al. 2018 (\"Practical Multiple Scattering for Rough Surfaces\") against it.\n"
      "Angles in degrees, measured from the surface normal, counter-clockwise positive\n"
      "(theta_i > 0: light from the upper left). Exit status: 0 ok, 1 a threshold exceeded, 2 bad input\n"
      "or output that could not be written, 3 internal error, 130 interrupted (Ctrl-C)."};
  app.set_version_flag("--version", std::string("vgroove ") + validation::version_string() + " (git " +
                                        validation::git_revision() + ")");
  app.require_subcommand(1);

  TraceArgs ta;
  auto* trace = app.add_subcommand("trace",
                                   "Trace a beam through one V-groove (symmetric or not) exactly; print the fraction "
                                   "of the beam and the exit angle per (facet hit first, bounce count k).");
  add_groove_options(trace, ta.groove);
  add_real(trace, "--theta-i-deg", ta.theta_i_deg, "incident angle theta_i in degrees, " + theta_i_range_text())
      ->capture_default_str();
  add_integer(trace, "--rays", ta.rays, "rays across the groove's opening", 1, kMaxRays)->capture_default_str();
  add_text(trace, "--sampling", ta.sampling, "ray placement: stratified (midpoints of equal strata) or random")
      ->capture_default_str();
  add_seed(trace, ta.seed, "seed of the random placement")->capture_default_str();
  add_integer(trace, "--max-bounces", ta.max_bounces,
              "bounce limit; rays past it are counted, not dropped (default: " + std::to_string(kDefaultMaxBounces) +
                  ", raised to the groove's bound ceil(180 / theta_v) + 1 for apertures narrow enough to need it)",
              1, kMaxBounces);
  trace->add_flag("--json", ta.json, "print JSON (the same shape as `analytic --json`)");

  AnalyticArgs aa;
  auto* an = app.add_subcommand("analytic",
                                "Evaluate the kaleidoscopic model (Eq. 4-6 symmetric, Eq. 7-9 nonsymmetric) for one "
                                "V-groove; same output as trace.");
  add_groove_options(an, aa.groove);
  add_real(an, "--theta-i-deg", aa.theta_i_deg, "incident angle theta_i in degrees, " + theta_i_range_text())
      ->capture_default_str();
  add_text(an, "--eq6-form", aa.eq6_form,
           "symmetric grooves: corrected (see docs/ERRATA.md) or printed (as in the paper)")
      ->capture_default_str();
  an->add_flag("--json", aa.json, "print JSON (the same shape as `trace --json`)");

  ValidateArgs va;
  auto* val = app.add_subcommand("validate",
                                 "Run a suite (sim against analytic), print the table beside the paper's "
                                 "figures, write the report JSON; exit 1 if a threshold is exceeded.");
  add_text(val, "suite", va.suite, "suite spec, e.g. data/suites/table1_symmetric.json")->required();
  add_text(val, "--out", va.out, "report JSON to write (refuses to overwrite without --force)");
  add_integer(val, "--rays", va.rays, "rays per lit facet (default: the suite's)", 1, kMaxRays);
  add_threads(val, va.threads);
  add_text(val, "--sampling", va.sampling,
           "override the suite's placement: stratified, random, or breakpoints (a grid of --rays stratified "
           "rays, then bisection between neighbours of different outcome down to adjacent doubles: exact "
           "fractions)");
  add_seed(val, va.seed, "override the suite's seed");
  add_text(val, "--eq6-form", va.eq6_form, "override the suite's form of Eq. 6: corrected or printed");
  add_text(val, "--model-table", va.model_table,
           "\"brdf\" suites: hold this table of a foreign model's bin-integrated lobes (layout from "
           "`vgroove bins SUITE`) against the simulation instead of vgroove's model");
  val->add_flag("--force", va.force, "overwrite an existing report");
  val->add_option("--shard", va.shard,
                  "I/N, 1 <= I <= N <= 100000: run only the I-th of N parts of the suite's work and write it to "
                  "--out as a partial report (`vgroove merge` joins them into this report)");

  auto* bench = app.add_subcommand("bench", "Benchmarks: what accuracy costs in time.");
  bench->require_subcommand(1);
  AccuracyArgs ac;
  auto* acc = bench->add_subcommand("accuracy",
                                    "Run a suite at several ray counts and placements; report max/mean "
                                    "L1 against rays and wall time.");
  add_text(acc, "suite", ac.suite, "suite spec")->required();
  add_integer(acc, "--rays", ac.rays, "rays per lit facet, comma-separated", 1, kMaxRays)
      ->delimiter(',')
      ->capture_default_str();
  add_text(acc, "--sampling", ac.samplings,
           "placements, comma-separated: stratified, random, breakpoints (--rays is then the grid's size)")
      ->delimiter(',')
      ->capture_default_str();
  add_threads(acc, ac.threads);
  add_text(acc, "--out", ac.out, "report JSON to write");
  acc->add_flag("--force", ac.force, "overwrite an existing report");
  add_text(acc, "--shard", ac.shard,
           "I/N, 1 <= I <= N <= 100000: run only the I-th of N parts and write it to --out as a partial "
           "report (`vgroove merge` joins them; each run's wall_s is then its summed case time)");

  ta.dry_run = aa.dry_run = va.dry_run = ac.dry_run = ctx.dry_run;
  ta.cancel = va.cancel = ac.cancel = ctx.cancel;
  PlotArgs pa;
  auto* plot = app.add_subcommand(
      "plot",
      "Draw a report with matplotlib (from the JSON alone, nothing recomputed): Table 1 heatmaps, the Fig. 11 "
      "grids, the furnace, Table 2, accuracy against time and cost, check_brdf. Runs python/vgroove/plot.py "
      "with Debian's python3 (VGROOVE_PYTHON names another); writes every figure or none.");
  add_text(plot, "report", pa.report, "report JSON (vgroove validate --out, vgroove bench accuracy --out)")->required();
  add_text(plot, "--out", pa.out,
           "image to write, or its base name (default: the report's name without .json); figures after "
           "the first get a suffix (-ggx-3d, -cost)");
  add_text(plot, "--format", pa.format, "png (default), svg or pdf");
  plot->add_flag("--force", pa.force, "overwrite existing images");
  pa.dry_run = ctx.dry_run;
  pa.cancel = ctx.cancel;
  SimulateArgs sa;
  auto* simu = app.add_subcommand("simulate",
                                  "Run a scene (data/scenes/*.json): trace every theta_i with the effects it "
                                  "chooses (Fresnel, histograms, energy per k); print a table, write the "
                                  "result JSON.");
  add_text(simu, "scene", sa.scene, "scene spec, e.g. data/scenes/gold_groove.json")->required();
  add_text(simu, "--out", sa.out, "result JSON to write (refuses to overwrite without --force)");
  add_threads(simu, sa.threads);
  simu->add_flag("--force", sa.force, "overwrite an existing result");
  add_text(simu, "--shard", sa.shard,
           "I/N, 1 <= I <= N <= 100000: run only the I-th of N parts and write it to --out as a partial "
           "report (`vgroove merge` joins them)");
  sa.dry_run = ctx.dry_run;
  sa.cancel = ctx.cancel;
  SampleArgs sma;
  auto* smp = app.add_subcommand(
      "sample",
      "Importance-sample the V-groove BRDF (Lee et al. 2018, Sec. 6; symmetric or, with --model "
      "vgroove-nonsymmetric, Eq. 23): draw --n exit directions, hold them "
      "to the sampler's pdf by a chi-square test (cells of (cos theta_o, phi_o), flatland theta_o; pdf integrated per "
      "cell) and report the weights rho cos / pdf; exit 1 if the chi-square rejects.");
  add_text(smp, "--ndf", sma.ndf, "normal distribution: ggx, beckmann or phong")->capture_default_str();
  add_real(smp, "--alpha", sma.alpha, "roughness alpha, " + support::interval_text(kMinAlpha, true, kMaxAlpha, true))
      ->capture_default_str();
  add_real(smp, "--theta-i-deg", sma.theta_i_deg,
           "incident angle in degrees, " + support::interval_text(0.0, true, kMaxSurfaceThetaIDeg, true))
      ->capture_default_str();
  add_integer(smp, "--n", sma.n, "samples", 1, kMaxRays)->capture_default_str();
  add_text(smp, "--strategy", sma.strategy,
           "facet distribution: printed (|s.n| D(s), the paper's), vndf (the V-cavity's visible normals), "
           "smith-vndf (Smith-GGX visible normals; ggx only) or bounded-vndf (Tokuyoshi and Eto 2024; ggx, "
           "3d only)")
      ->capture_default_str();
  add_text(smp, "--dim", sma.dim, "3d or flatland")->capture_default_str();
  add_text(smp, "--model", sma.model,
           "vgroove (symmetric grooves, Eq. 16) or vgroove-nonsymmetric (Eq. 23, the partner's tilt from the "
           "tabulated inverse CDF of P(theta_r); phong alpha <= 1; its pdf costs ~1 ms: use --n ~10^4 to "
           "10^5 and, in 3d, few cells)")
      ->capture_default_str();
  auto* smp_max_k = add_integer(smp, "--max-k", sma.max_k,
                                "paths with more reflections return zero weight, counted as lost beyond max_k "
                                "(default " +
                                    std::to_string(analytic::kSamplerMaxK) + "; vgroove-nonsymmetric " +
                                    std::to_string(analytic::kNonsymmetricSamplerMaxK) + ", its pdf costs O(max_k))",
                                1, kMaxSamplerK);
  add_seed(smp, sma.seed, "seed of the uniform numbers")->capture_default_str();
  add_integer(smp, "--cos-bins", sma.cos_bins, "3d: cells over cos theta_o in [0, 1]", 1, kMaxSampleCosBins)
      ->capture_default_str();
  add_integer(smp, "--phi-bins", sma.phi_bins, "3d: cells over phi_o, even", 2, kMaxSamplePhiBins)
      ->capture_default_str();
  add_integer(smp, "--theta-bins", sma.theta_bins, "flatland: cells over theta_o in (-90, 90)", 1, kMaxSampleThetaBins)
      ->capture_default_str();
  add_text(smp, "--out", sma.out, "result JSON to write (the chi-square table, observed and expected per cell)");
  smp->add_flag("--force", sma.force, "overwrite an existing result");
  smp->callback([&sma, smp_max_k]() { sma.max_k_given = smp_max_k->count() > 0; });
  sma.dry_run = ctx.dry_run;
  sma.cancel = ctx.cancel;
  BinsArgs bi;
  auto* bins = app.add_subcommand("bins",
                                  "Write a \"brdf\" suite's bin layout (cases, bin edges, frame) as JSON: fill in a "
                                  "model's flux per bin and run `vgroove validate SUITE --model-table FILE`.");
  add_text(bins, "suite", bi.suite, "suite spec of kind \"brdf\", e.g. data/suites/fig11.json")->required();
  add_text(bins, "--out", bi.out, "layout JSON to write (default: stdout)");
  bins->add_flag("--force", bi.force, "overwrite an existing file");
  bi.dry_run = ctx.dry_run;
  BrdfArgs ba;
  auto* brdf = app.add_subcommand(
      "brdf",
      "Evaluate a BRDF at a pair of directions (or every pair of a JSON file): vgroove's multiple-scattering "
      "model (Lee et al. 2018, Eq. 16-17), its nonsymmetric form (Eq. 21-23, partner facets by Eq. 20; "
      "anisotropic with --alpha-y) or Cook-Torrance (Eq. 1-3, V-cavity G), F = 1. 3D: polar angles from the "
      "normal, azimuths about it (phi_o = phi_i + 180 is the mirror side; with --alpha-y from the --alpha "
      "axis); flatland: signed angles.");
  add_text(brdf, "--model", ba.model, "vgroove, vgroove-nonsymmetric or cook-torrance")->capture_default_str();
  add_text(brdf, "--ndf", ba.ndf, "ggx, beckmann or phong")->capture_default_str();
  add_real(brdf, "--alpha", ba.alpha,
           "roughness, " + support::interval_text(kMinAlpha, true, kMaxAlpha, true) +
               "; vgroove-nonsymmetric with phong and --partner independent: below sqrt 2 (Eq. 20 needs it); "
               "alpha_x with --alpha-y")
      ->capture_default_str();
  auto* brdf_alpha_y =
      add_real(brdf, "--alpha-y", ba.alpha_y,
               "vgroove-nonsymmetric, 3D, ggx or beckmann only: the roughness across the --alpha "
               "axis, " +
                   support::interval_text(kMinAlpha, true, kMaxAlpha, true) + " (default: --alpha, isotropic)");
  auto* brdf_partner =
      add_text(brdf, "--partner", ba.partner,
               "vgroove-nonsymmetric only: the partner facet's tilt, independent (Eq. 20) or symmetric (equal to the "
               "first's: the symmetric model, anisotropic with --alpha-y)")
          ->capture_default_str();
  add_text(brdf, "--dim", ba.dim, "3d or flatland")->capture_default_str();
  add_real(brdf, "--theta-i-deg", ba.theta_i_deg, "light: polar angle, [0, 90) (flatland: signed, (-90, 90))")
      ->capture_default_str();
  add_real(brdf, "--phi-i-deg", ba.phi_i_deg, "light: azimuth, [-360, 360] (3D only)")->capture_default_str();
  auto* theta_o = add_real(brdf, "--theta-o-deg", ba.theta_o_deg,
                           "viewer: polar angle, [0, 90] (flatland: signed, [-90, 90]); required "
                           "unless --directions");
  add_real(brdf, "--phi-o-deg", ba.phi_o_deg, "viewer: azimuth, [-360, 360] (3D only)")->capture_default_str();
  auto* brdf_max_k = add_integer(
      brdf, "--max-k", ba.max_k,
      "orders summed; vgroove 3D and cook-torrance: any, at no extra cost (default: all); vgroove "
      "flatland: <= 4096, O(max_k^2) (default 4096); vgroove-nonsymmetric: <= 1024, O(max_k^2) (default 64)",
      1, std::numeric_limits<int>::max());
  brdf->add_flag("--per-k", ba.per_k, "also print each order k = 1..--per-k-max");
  add_integer(brdf, "--per-k-max", ba.per_k_max, "orders printed one by one with --per-k", 1, 1000)
      ->capture_default_str();
  add_text(brdf, "--directions", ba.directions,
           "JSON file {\"directions\": [{\"theta_i_deg\", \"theta_o_deg\"[, \"phi_i_deg\", "
           "\"phi_o_deg\"]}, ...]}: evaluate at every pair");
  brdf->add_flag("--json", ba.json, "print JSON");
  brdf->callback([&ba, theta_o, brdf_alpha_y, brdf_partner, brdf_max_k]() {
    ba.theta_o_given = theta_o->count() > 0;
    ba.alpha_y_given = brdf_alpha_y->count() > 0;
    ba.partner_given = brdf_partner->count() > 0;
    ba.max_k_given = brdf_max_k->count() > 0;
  });
  ba.dry_run = ctx.dry_run;
  ba.cancel = ctx.cancel;
  EnergyArgs ea;
  auto* energy = app.add_subcommand(
      "energy",
      "Exact energy tables: the directional albedo E(mu, alpha) of V-groove surfaces per bounce order k (F = 1; "
      "E_1 what single scattering keeps, the rest what it loses), traced with every ray in a groove of its own "
      "drawn from the NDF, with standard errors, beside the analytic model (quadrature) and Cook-Torrance.");
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
  add_text(energy, "--shard", ea.shard,
           "I/N, 1 <= I <= N <= 100000: run only the I-th of N parts and write it to --out as a partial "
           "report (`vgroove merge` joins them)");
  energy->add_flag("--force", ea.force, "overwrite existing files");
  energy->add_flag("--audit", ea.audit,
                   "the energy audit over the grid (GGX and Beckmann; --rays: walk paths per cell): compensation "
                   "formulas against the V-groove model and the Smith random walk (its report's /spec is a suite for "
                   "`vgroove validate`, which shards and runs under mpirun)");
  add_text(energy, "--export", ea.export_base,
           "write tables engines can load to BASE.json, .npz, .h, .png, .exr (see --formats): E_ss, E_avg, the DFG "
           "scale and bias, and with --ms-reference the exact multiple-scattering albedo per F0");
  add_text(energy, "--layout", ea.layout, "--export's layout: cycles (32 texel ends, Cycles' table_ggx_E) or centres")
      ->capture_default_str();
  add_integer(energy, "--size", ea.size, "--export's texels per axis", 2, kMaxExportSize)->capture_default_str();
  add_text(energy, "--masking", ea.masking, "--export's G2 without --ms-reference: smith, smith_separable, vcavity")
      ->capture_default_str();
  add_text(energy, "--ms-reference", ea.ms_reference,
           "--export's multiple scattering: none, vgroove (V-cavity single scattering), smith_walk (Smith's; "
           "--rays paths per texel)")
      ->capture_default_str();
  add_real(energy, "--ms-F0", ea.ms_F0, "--export's Schlick F0 axis, comma-separated, each in [0, 1]")->delimiter(',');
  add_list(energy, "--formats", ea.formats, "--export's files, comma-separated: json, npz, h, png, exr")
      ->capture_default_str();
  ea.dry_run = ctx.dry_run;
  ea.cancel = ctx.cancel;
  MergeArgs ma;
  auto* merge = app.add_subcommand(
      "merge",
      "Join the partial reports of one sharded run (--shard 1/N ... N/N) into the report the run gives in one "
      "process, bit for bit (timings aside). Refuses parts of different runs, versions or splits, missing or "
      "repeated shards, and damaged files.");
  add_text(merge, "parts", ma.parts, "partial reports, in any order")->required();
  add_text(merge, "--out", ma.out, "report to write (refuses to overwrite without --force)");
  merge->add_flag("--npy", ma.npy, "energy tables: the arrays as .npy files beside the JSON");
  merge->add_flag("--force", ma.force, "overwrite existing files");
  ma.dry_run = ctx.dry_run;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, like every other input error.
    print_error(std::string(e.what()) + " (see vgroove --help)");
    return 2;
  } catch (const support::UserError& e) {
    print_error(e.what());
    return 2;
  }
  try {
    if (*trace) return cmd_trace(ta);
    if (*an) return cmd_analytic(aa);
    if (*val) return cmd_validate(va);
    if (*acc) return cmd_bench_accuracy(ac);
    if (*plot) return cmd_plot(pa);
    if (*simu) return cmd_simulate(sa);
    if (*smp) return cmd_sample(sma);
    if (*brdf) return cmd_brdf(ba);
    if (*bins) return cmd_bins(bi);
    if (*energy) return cmd_energy(ea);
    if (*merge) return cmd_merge(ma);
  } catch (const support::UserError& e) {
    print_error(e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    print_error(
        "out of memory: the run needs more memory than this process may use (fewer rays, cases, grooves, "
        "bins or threads need less)");
    return 2;
  } catch (const RankFailure& e) {
    print_error(std::string(e.what()) + "; no report written");
    return e.interrupted ? kExitInterrupted : 3;
  } catch (const std::exception& e) {
    std::cerr << "vgroove: internal error: " << support::printable(e.what()) << "\n";
    return 3;
  }
  return 0;
}

}  // namespace

namespace {
// The comma-separated list options (energy's grid, bench accuracy's runs): CLI11 drops empty items
// and runs a repeated one twice, so both are refused here, naming the option: "" when fine.
std::string list_problem(int argc, const char* const* argv) {
  static const char* const kLists[] = {"--ndf", "--dim", "--mu", "--alpha", "--rays", "--sampling"};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    std::string name = arg, value;
    if (const auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos)
      name = arg.substr(0, eq), value = arg.substr(eq + 1);
    else if (i + 1 < argc)
      value = argv[i + 1];
    if (std::find(std::begin(kLists), std::end(kLists), name) == std::end(kLists) ||
        value.find(',') == std::string::npos)
      continue;
    std::vector<std::string> items;
    for (std::size_t b = 0;;) {
      const std::size_t e = value.find(',', b);
      items.push_back(value.substr(b, e == std::string::npos ? std::string::npos : e - b));
      if (e == std::string::npos) break;
      b = e + 1;
    }
    for (std::size_t n = 0; n < items.size(); ++n) {
      if (items[n].empty())
        return name + " = \"" + value + "\" has an empty item (items are separated by single commas)";
      for (std::size_t m = 0; m < n; ++m)
        if (items[m] == items[n])
          return name + " = \"" + value + "\" gives " + items[n] + " twice (each item is run once: give it once)";
    }
  }
  return "";
}
}  // namespace

int run_cli(int argc, const char* const* argv, const CliContext& ctx) {
  // Paths and names reach the reports as JSON text, which holds UTF-8 only: refused before the work.
  for (int i = 1; i < argc; ++i)
    if (!support::valid_utf8(argv[i])) {
      print_error("argument " + std::to_string(i) + " = \"" + std::string(argv[i]) +
                  "\" is not valid UTF-8 (reports hold paths and names as JSON text): rename it or give another path");
      return 2;
    }
  if (const std::string problem = list_problem(argc, argv); !problem.empty()) {
    print_error(problem);
    return 2;
  }
  const int status = run_command(argc, argv, ctx);
  // Output that did not reach its destination (a full disk, a closed stdout) is a failure.
  if (const std::string failed = support::flush_standard_output(); !failed.empty()) {
    print_error(failed);
    return status == kExitInterrupted ? status : 2;
  }
  return status;
}

}  // namespace vgroove::app
