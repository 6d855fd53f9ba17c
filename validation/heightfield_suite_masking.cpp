// The masking section of the "heightfield" suite (validation/heightfield_suite.h): traced G1 and
// G2 per case on its fields, their means and errors over the fields, and the models.
#include "vgroove/analytic/masking_shadowing.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/rng.h"
#include "vgroove/validation/heightfield_suite.h"
#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::validation {

namespace {

// Streams of the suite's seed for the masking points: G1 and G2.
constexpr std::uint64_t kG1Seeds = 0x686667316dULL, kG2Seeds = 0x686667326dULL;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::uint64_t point_seed(std::uint64_t seed, std::uint64_t stream, std::size_t case_index, std::size_t item,
                         int field) {
  const std::uint64_t key =
      (static_cast<std::uint64_t>(case_index) * 4096 + item) * 65536 + static_cast<std::uint64_t>(field);
  return sim::Rng(seed, stream, key).next_u64();
}

// Mean over the fields and its standard error: the fields' spread, at least the binomial error of
// the points counted (p the mean); NaN when a field has no value.
void mean_se(const std::vector<double>& v, double points, double& mean, double& se) {
  const double n = static_cast<double>(v.size());
  double s = 0.0;
  for (double x : v) s += x;
  mean = s / n;
  double var = 0.0;
  for (double x : v) var += (x - mean) * (x - mean);
  const double p = std::clamp(mean, 0.0, 1.0);
  // p (1 - p) at least 1 / points: a bin seen whole (or hidden whole) on every field still has
  // the error of its points (as the V-groove tests' binomial bound).
  se = std::max(std::sqrt(var / (n - 1.0) / n),
                points > 0.0 ? std::sqrt(std::max(p * (1.0 - p), 1.0 / points) / points) : kNaN);
  if (!std::isfinite(mean)) se = kNaN;
}

// The traced value over the fields from per-field G (overall) and per-bin G with point counts.
template <class G, class GBin, class Count>
HeightfieldMaskingValue traced_value(int bins, int fields, G&& g, GBin&& g_bin, Count&& count, double front) {
  HeightfieldMaskingValue v;
  std::vector<double> x;
  for (int r = 0; r < fields; ++r) x.push_back(g(r));
  mean_se(x, front, v.g, v.g_se);
  for (int b = 0; b < bins; ++b) {
    x.clear();
    std::int64_t pts = 0;
    for (int r = 0; r < fields; ++r) x.push_back(g_bin(r, b)), pts += count(r, b);
    double m = 0.0, se = 0.0;
    mean_se(x, static_cast<double>(pts), m, se);
    v.bins.push_back(m), v.bins_se.push_back(se), v.bin_points.push_back(pts);
  }
  return v;
}

// The bin of the tallies (sim/heightfield_masking.h): theta_m equal over [0, pi/2), the normal's
// azimuth relative to phi_o with bin 0 centred on it.
analytic::NormalBin normal_bin(const HeightfieldMaskingSpec& m, int b, double phi_o) {
  const int t = b / m.phi_m_bins, p = b % m.phi_m_bins;
  const double tw = 0.5 * std::numbers::pi / m.theta_m_bins, pw = 2.0 * std::numbers::pi / m.phi_m_bins;
  return {t * tw, (t + 1) * tw, phi_o + (p - 0.5) * pw, phi_o + (p + 0.5) * pw};
}

}  // namespace

HeightfieldMaskingMiss heightfield_masking_miss(const std::string& name, const HeightfieldMaskingValue& t, double value,
                                                std::vector<double> bins, double sigmas, double tolerance) {
  HeightfieldMaskingMiss m;
  m.model = name;
  m.value = value;
  m.bins = std::move(bins);
  m.diff = t.g - value;
  m.z = m.diff / t.g_se;
  m.overall_within_noise = std::abs(m.diff) <= sigmas * t.g_se + tolerance;
  m.within_noise = m.overall_within_noise;
  double worst = -1.0;
  for (std::size_t b = 0; b < m.bins.size(); ++b) {
    if (!std::isfinite(t.bins[b])) continue;  // a field without points in the bin
    const double d = t.bins[b] - m.bins[b];
    const double excess = std::abs(d) - (sigmas * t.bins_se[b] + tolerance);
    m.within_noise = m.within_noise && excess <= 0.0;
    const double z = d / t.bins_se[b];
    if (std::abs(z) > worst)
      worst = std::abs(z), m.worst_bin = static_cast<int>(b), m.worst_bin_diff = d, m.worst_bin_z = z;
  }
  return m;
}

HeightfieldMaskingSpec parse_heightfield_masking(support::JsonObject& m) {
  HeightfieldMaskingSpec s;
  s.theta_o_deg = read_numbers(m, "theta_o_deg", 0.0, true, kMaxSurfaceThetaIDeg, true);
  s.phi_deg = read_numbers(m, "phi_deg", 0.0, true, 180.0, true);
  s.points = static_cast<long>(m.integer("points", 1, kMaxRays));
  s.theta_m_bins = static_cast<int>(m.integer_or("theta_m_bins", s.theta_m_bins, 1, 90));
  s.phi_m_bins = static_cast<int>(m.integer_or("phi_m_bins", s.phi_m_bins, 1, 360));
  m.finish();
  return s;
}

void trace_masking_field(const HeightfieldSuite& suite, std::size_t case_index, int field,
                         const sim::HeightfieldSurface& s, HeightfieldMaskingFields& out,
                         const std::atomic<bool>* cancel) {
  const HeightfieldMaskingSpec& m = *suite.masking;
  const HeightfieldCase c = suite.case_at(case_index);
  out.g1.resize(m.theta_o_deg.size());
  out.g2.resize(m.pairs());
  for (std::size_t t = 0; t < m.theta_o_deg.size(); ++t) {
    if (support::cancelled(cancel)) return;
    sim::HeightfieldMaskingOptions o;
    o.theta_o = deg_to_rad(m.theta_o_deg[t]);
    o.points = m.points;
    o.seed = point_seed(suite.seed, kG1Seeds, case_index, t, field);
    o.theta_m_bins = m.theta_m_bins, o.phi_m_bins = m.phi_m_bins;
    out.g1[t].push_back(sim::heightfield_masking(s, o));
  }
  for (std::size_t t = 0; t < m.theta_o_deg.size(); ++t)
    for (std::size_t p = 0; p < m.phi_deg.size(); ++p) {
      if (support::cancelled(cancel)) return;
      const std::size_t pair = t * m.phi_deg.size() + p;
      sim::HeightfieldJointMaskingOptions o;
      o.theta_i = deg_to_rad(c.theta_i_deg), o.phi_i = 0.0;
      o.theta_o = deg_to_rad(m.theta_o_deg[t]), o.phi_o = deg_to_rad(m.phi_deg[p]);
      o.points = m.points;
      o.seed = point_seed(suite.seed, kG2Seeds, case_index, pair, field);
      o.theta_m_bins = m.theta_m_bins, o.phi_m_bins = m.phi_m_bins;
      out.g2[pair].push_back(sim::heightfield_joint_masking(s, o));
    }
}

void finish_masking(const HeightfieldSuite& suite, const HeightfieldMaskingFields& traced, HeightfieldOutcome& out) {
  const HeightfieldMaskingSpec& m = *suite.masking;
  const analytic::NdfKind ndf = out.c.ndf;
  const double alpha = out.c.alpha, theta_i = deg_to_rad(out.c.theta_i_deg);
  const double sig = suite.sigmas, tol = suite.model_tolerance;
  const int bins = m.bins(), nf = suite.fields;
  const analytic::NormalBin all{0.0, 0.5 * std::numbers::pi, -std::numbers::pi, std::numbers::pi};
  const double lambda_i = analytic::Lambda(ndf, theta_i, alpha);
  for (std::size_t t = 0; t < m.theta_o_deg.size(); ++t) {
    const auto& f = traced.g1[t];
    double front = 0.0;
    for (const auto& x : f) out.masking_points += x.points, out.masking_lost += x.lost, front += x.front;
    HeightfieldMaskingValue v = traced_value(
        bins, nf, [&](int r) { return f[r].g1(); }, [&](int r, int b) { return f[r].g1(b); },
        [&](int r, int b) { return f[r].count[b]; }, front);
    v.theta_o_deg = m.theta_o_deg[t];
    const double theta_o = deg_to_rad(v.theta_o_deg);
    const double smith = 1.0 / (1.0 + analytic::Lambda(ndf, theta_o, alpha));
    std::vector<double> vb;
    for (int b = 0; b < bins; ++b)
      vb.push_back(analytic::vcavity_g1_bin_average(ndf, alpha, theta_o, 0.0, normal_bin(m, b, 0.0)));
    v.models.push_back(heightfield_masking_miss("smith", v, smith, std::vector<double>(bins, smith), sig, tol));
    v.models.push_back(heightfield_masking_miss(
        "vcavity", v, analytic::vcavity_g1_bin_average(ndf, alpha, theta_o, 0.0, all), vb, sig, tol));
    out.g1.push_back(std::move(v));
  }
  for (std::size_t t = 0; t < m.theta_o_deg.size(); ++t)
    for (std::size_t p = 0; p < m.phi_deg.size(); ++p) {
      const auto& f = traced.g2[t * m.phi_deg.size() + p];
      double front = 0.0;
      for (const auto& x : f) out.masking_points += x.points, out.masking_lost += x.lost, front += x.front;
      HeightfieldMaskingValue v = traced_value(
          bins, nf, [&](int r) { return f[r].g2(); }, [&](int r, int b) { return f[r].g2(b); },
          [&](int r, int b) { return f[r].count[b]; }, front);
      v.theta_o_deg = m.theta_o_deg[t], v.phi_deg = m.phi_deg[p];
      double gi = 0.0, go = 0.0;
      for (const auto& x : f) gi += x.g1_i(), go += x.g1_o();
      v.g1_i = gi / nf, v.g1_o = go / nf;
      const double theta_o = deg_to_rad(v.theta_o_deg), phi_o = deg_to_rad(v.phi_deg);
      const double lambda_o = analytic::Lambda(ndf, theta_o, alpha);
      const auto smith = [&](const char* name, double g) {
        v.models.push_back(heightfield_masking_miss(name, v, g, std::vector<double>(bins, g), sig, tol));
      };
      smith("smith_separable", analytic::G2_smith_separable(lambda_i, lambda_o));
      smith("smith_height_correlated", analytic::G2_smith_height_correlated(lambda_i, lambda_o));
      smith("smith_height_direction_correlated",
            analytic::G2_smith_height_direction_correlated(lambda_i, lambda_o, phi_o));
      std::vector<double> vb;
      for (int b = 0; b < bins; ++b)
        vb.push_back(
            analytic::vcavity_g2_bin_average(ndf, alpha, theta_i, 0.0, theta_o, phi_o, normal_bin(m, b, phi_o)));
      v.models.push_back(heightfield_masking_miss(
          "vcavity", v, analytic::vcavity_g2_bin_average(ndf, alpha, theta_i, 0.0, theta_o, phi_o, all), vb, sig, tol));
      out.g2.push_back(std::move(v));
    }
}

}  // namespace vgroove::validation
