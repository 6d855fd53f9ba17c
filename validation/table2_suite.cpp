#include "vgroove/validation/table2_suite.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/support/format.h"
#include "vgroove/support/printable.h"
#include "vgroove/validation/case_surface.h"
#include "vgroove/validation/detail/part_fields.h"

#include "vgroove/analytic/bounce_percentiles.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"
#include "vgroove/validation/table_frame.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace vgroove::validation {

namespace {

using support::Clock;
using support::seconds_since;

}  // namespace

namespace {
constexpr analytic::PercentileMeasure kOtherMeasures[] = {analytic::PercentileMeasure::solid_angle,
                                                          analytic::PercentileMeasure::flatland};

// The q-th percentile of the traced bounce counts: the smallest k with at least the fraction q of
// the escaped rays at k bounces or fewer.
int percentile_of_counts(const std::vector<std::int64_t>& by_k, double q) {
  std::int64_t total = 0;
  for (auto c : by_k) total += c;
  std::int64_t run = 0;
  for (std::size_t k = 0; k < by_k.size(); ++k) {
    run += by_k[k];
    if (static_cast<double>(run) >= q * static_cast<double>(total)) return static_cast<int>(k);
  }
  return static_cast<int>(by_k.size()) - 1;
}
}  // namespace

Table2Suite parse_table2_suite(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  Table2Suite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  root.one_of("kind", {"table2"});
  s.ndfs = read_ndfs(root);
  s.alphas = read_numbers(root, "alpha", kMinAlpha, true, kMaxAlpha, true);
  for (double p : read_numbers(root, "percentiles", 0.0, false, 100.0, false)) s.percentiles.push_back(p / 100.0);
  s.rays = static_cast<long>(root.integer("rays", 1, kMaxRays));
  s.grooves = static_cast<int>(root.integer("grooves", 1, kMaxGrooves));
  s.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, 0, kMaxSeed));
  support::JsonObject paper = root.object("paper");
  s.source = paper.string("source");
  const nlohmann::json& rows = paper.raw("max_bounces");
  const std::size_t per_row = s.ndfs.size() * s.alphas.size();
  if (!rows.is_array() || rows.size() != s.percentiles.size())
    paper.fail("max_bounces",
               "must be a list of " + std::to_string(s.percentiles.size()) + " rows (one per percentile)");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (!rows[r].is_array() || rows[r].size() != per_row)
      throw support::UserError(file + ": " + paper.path("max_bounces") + "/" + std::to_string(r) +
                               " must be a list of " + std::to_string(per_row) + " integers (ndf outer, alpha inner)");
    for (std::size_t n = 0; n < per_row; ++n) {
      if (!rows[r][n].is_number_integer() || rows[r][n].get<long long>() < 1 ||
          rows[r][n].get<long long>() > kMaxPaperBounces)
        throw support::UserError(file + ": " + paper.path("max_bounces") + "/" + std::to_string(r) + "/" +
                                 std::to_string(n) + " = " + support::value_text(rows[r][n]) +
                                 " must be an integer in [1, " + std::to_string(kMaxPaperBounces) + "]");
      s.paper.push_back(rows[r][n].get<int>());
    }
  }
  paper.finish();
  root.finish();
  return s;
}

double table2_run_memory_bytes(const Table2Suite& s, int threads) {
  const double surfaces = static_cast<double>(s.ndfs.size() * s.alphas.size());
  const double workers = std::min<double>(support::resolve_threads(threads), surfaces);
  const double groove = sizeof(sim::Groove) + 8.0 + 8.0 + sizeof(sim::GrooveFrame3d);
  const double entries = static_cast<double>(s.percentiles.size()) * surfaces;
  // Per worker a surface and an item's counts; per surface its merged counts (held twice while
  // merged); per table entry its figures.
  return workers * (s.grooves * groove + 1002.0 * 8.0) + 2.0 * surfaces * 1002.0 * 8.0 +
         entries * (4.0 * sizeof(int) + 1024.0);
}

std::shared_ptr<const Table2Work::Context> Table2Work::prepare(std::size_t unit) const {
  const std::size_t na = suite.alphas.size();
  auto ctx = std::make_shared<Context>();
  ctx->surface =
      make_case_surface(SurfaceDim::three_d, suite.ndfs[unit / na], suite.alphas[unit % na], suite.grooves, suite.seed)
          .three_d;
  return ctx;
}

sim::BounceCounts Table2Work::run_chunks(const Context& ctx, std::size_t, std::int64_t begin, std::int64_t end) const {
  // The simulation column: procedural 3D surfaces lit at normal incidence, bounce counts traced.
  sim::Microsurface3dTraceOptions to;
  to.theta_i = 0.0;
  to.rays = rays;
  to.seed = suite.seed;
  to.theta_bins = 1;
  to.phi_bins = 2;
  to.max_k = kTable2MaxK;
  sim::BounceCounts out(kTable2MaxK);
  for (std::int64_t c = begin; c < end && !support::cancelled(cancel); ++c) {
    const sim::Microsurface3dTally t = sim::trace_microsurface3d_chunk(ctx.surface, to, c);
    out.merge_fates(t);
    for (std::size_t k = 0; k < out.by_k.size(); ++k) out.by_k[k] += t.by_k[k];
  }
  return out;
}

nlohmann::json Table2Work::tally_json(const Tally& t) {
  nlohmann::json j = fates_json(t);
  j["by_k"] = t.by_k;
  return j;
}

sim::BounceCounts Table2Work::read_tally(support::JsonObject& j, std::size_t, const std::vector<ChunkRun>& runs) const {
  return read_bounce_counts(j, kTable2MaxK, rays_in_chunks(runs, rays, sim::kRaysPerChunk),
                            sim::TraceOptions{}.max_bounces);
}

Job<Table2Work> table2_job(const Table2Suite& s, long rays, nlohmann::json descriptor) {
  const long n_rays = rays > 0 ? rays : s.rays;
  // Cost: about 300 ns per ray at normal incidence on a 3D surface (its many narrow grooves).
  std::vector<support::WorkUnit> units(s.ndfs.size() * s.alphas.size());
  for (auto& u : units) {
    u.chunks = (n_rays + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
    u.chunk_cost = 300 * std::min<std::int64_t>(n_rays, sim::kRaysPerChunk);
  }
  return make_job(Table2Work{s, n_rays}, std::move(units), std::move(descriptor));
}

Table2Run table2_run_from(const Table2Suite& s, const std::vector<UnitResult<Table2Work>>& results,
                          const std::atomic<bool>* cancel) {
  Table2Run run;
  const std::size_t na = s.alphas.size(), nn = s.ndfs.size(), nq = s.percentiles.size();
  auto at = [&](std::size_t q, std::size_t n, std::size_t a) { return (q * nn + n) * na + a; };
  run.ours.resize(nq * nn * na);
  run.alternatives.assign(std::size(kOtherMeasures), std::vector<int>(nq * nn * na));
  run.traced.resize(nq * nn * na);
  if (!results.empty()) run.rays = static_cast<long>(results.front().tally.rays);
  for (std::size_t q = 0; q < nq; ++q)
    for (std::size_t n = 0; n < nn; ++n)
      for (std::size_t a = 0; a < na; ++a) {
        if (support::cancelled(cancel)) {
          run.interrupted = true;
          return run;
        }
        run.ours[at(q, n, a)] = analytic::max_bounces_at_percentile(s.ndfs[n], s.alphas[a], s.percentiles[q],
                                                                    analytic::PercentileMeasure::projected_area);
        for (std::size_t m = 0; m < std::size(kOtherMeasures); ++m)
          run.alternatives[m][at(q, n, a)] =
              analytic::max_bounces_at_percentile(s.ndfs[n], s.alphas[a], s.percentiles[q], kOtherMeasures[m]);
        run.agree += run.ours[at(q, n, a)] == s.paper[at(q, n, a)];
        run.traced[at(q, n, a)] = percentile_of_counts(results[n * na + a].tally.by_k, s.percentiles[q]);
      }
  run.pass = run.agree == static_cast<int>(run.ours.size());
  return run;
}

Table2Run run_table2_suite(const Table2Suite& s, long rays, int threads, const std::atomic<bool>* cancel) {
  const auto t0 = Clock::now();
  auto job = table2_job(s, rays, {});
  job.work.cancel = cancel;
  const auto results = run_job(job, threads, {}, cancel);
  Table2Run run;
  if (results) run = table2_run_from(s, *results, cancel);
  run.threads = support::resolve_threads(threads);
  run.interrupted = run.interrupted || !results;
  run.wall_s = seconds_since(t0);
  return run;
}

nlohmann::json table2_report_json(const Table2Suite& s, const Table2Run& run) {
  nlohmann::json j = report_header({s.name, s.file, "table2", s.description, s.seed}, run.threads, run.wall_s);
  j["rays"] = run.rays;
  j["source"] = s.source;
  j["assumptions"] = {
      {"percentile_measure",
       "projected area: D(s) cos(theta_s) ds, the fraction of the macrosurface under facets "
       "flatter than theta_m (the paper's sampling pdf |s.n| D(s), Sec. 6)"},
      {"incident_angle",
       "normal incidence: N = Eq. (4) at theta_i = 0, floor(pi / theta_v) + 1, theta_v = pi - 2 theta_m"},
      {"phong_exponent", "alpha_p = 2 / alpha^2 - 2 (Walter et al. 2007)"}};
  nlohmann::json rows = nlohmann::json::array();
  const std::size_t na = s.alphas.size(), nn = s.ndfs.size();
  for (std::size_t q = 0; q < s.percentiles.size(); ++q)
    for (std::size_t n = 0; n < nn; ++n)
      for (std::size_t a = 0; a < na; ++a) {
        const std::size_t i = (q * nn + n) * na + a;
        nlohmann::json alt;
        for (std::size_t m = 0; m < std::size(kOtherMeasures); ++m)
          alt[analytic::percentile_measure_name(kOtherMeasures[m])] = run.alternatives[m][i];
        rows.push_back({{"percentile", 100.0 * s.percentiles[q]},
                        {"ndf", analytic::ndf_name(s.ndfs[n])},
                        {"alpha", s.alphas[a]},
                        {"paper", s.paper[i]},
                        {"ours", run.ours[i]},
                        {"agree", run.ours[i] == s.paper[i]},
                        {"other_readings", alt},
                        {"traced_percentile_k", run.traced[i]}});
      }
  j["entries"] = rows;
  j["summary"] = {
      {"entries", run.ours.size()}, {"agree", run.agree}, {"rays_per_surface", s.rays}, {"grooves", s.grooves}};
  j["pass"] = run.pass;
  return j;
}

void print_table2(std::ostream& os, const Table2Suite& s, const Table2Run& run) {
  print_table_title(os, s.name, "table2", "maximum bounces at percentiles of D (" + support::printable(s.source) + ")",
                    run.threads);
  os << "  cell: paper / ours (projected-area percentile, Eq. 4 at theta_i = 0) / traced percentile of k\n";
  std::string head = "  perc.  ";
  for (auto n : s.ndfs)
    for (double a : s.alphas) {
      head += support::format(" %8.8s %-4.2g", analytic::ndf_name(n), a);
    }
  os << head << "\n";
  const std::size_t na = s.alphas.size(), nn = s.ndfs.size();
  for (std::size_t q = 0; q < s.percentiles.size(); ++q) {
    std::string row = support::format("  %4.0f%%  ", 100.0 * s.percentiles[q]);
    for (std::size_t n = 0; n < nn; ++n)
      for (std::size_t a = 0; a < na; ++a) {
        const std::size_t i = (q * nn + n) * na + a;
        row += support::format(" %4d/%-3d/%-4d", s.paper[i], run.ours[i], run.traced[i]);
      }
    os << row << "\n";
  }
  print_table_close(os, static_cast<std::size_t>(run.agree), run.ours.size(), run.wall_s,
                    support::format("entries agree with the paper; %ld rays per traced surface", run.rays));
}

}  // namespace vgroove::validation
