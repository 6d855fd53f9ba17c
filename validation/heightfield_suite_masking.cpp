// The masking section of the "heightfield" suite (validation/heightfield_suite.h): traced G1 and
// G2 per case on its fields, their means and errors over the fields, the models, and the masking
// controls (parsed, looked up, reported).
#include "vgroove/analytic/masking_shadowing.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/format.h"
#include "vgroove/support/user_error.h"
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
// azimuth relative to phi_ref (G1: phi_o; G2: the pair's bisector) with bin 0 centred on it.
analytic::NormalBin normal_bin(const HeightfieldMaskingSpec& m, int b, double phi_ref) {
  const int t = b / m.phi_m_bins, p = b % m.phi_m_bins;
  const double tw = 0.5 * std::numbers::pi / m.theta_m_bins, pw = 2.0 * std::numbers::pi / m.phi_m_bins;
  return {t * tw, (t + 1) * tw, phi_ref + (p - 0.5) * pw, phi_ref + (p + 0.5) * pw};
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

HeightfieldMaskingSpec parse_heightfield_masking(support::JsonObject& m, const HeightfieldSuite& suite) {
  HeightfieldMaskingSpec s;
  s.theta_o_deg = read_numbers(m, "theta_o_deg", 0.0, true, kMaxSurfaceThetaIDeg, true);
  s.phi_deg = read_numbers(m, "phi_deg", 0.0, true, 180.0, true);
  s.points = static_cast<long>(m.integer("points", 1, kMaxRays));
  s.theta_m_bins = static_cast<int>(m.integer_or("theta_m_bins", s.theta_m_bins, 1, 90));
  s.phi_m_bins = static_cast<int>(m.integer_or("phi_m_bins", s.phi_m_bins, 1, 360));
  if (m.has("controls")) {
    const nlohmann::json& cs = m.raw("controls");
    if (!cs.is_array())
      m.fail("controls", "must be an array of {g, model, ndf, alpha, theta_i_deg, theta_o_deg, phi_deg, every_bin}");
    for (std::size_t n = 0; n < cs.size(); ++n) {
      support::JsonObject c(cs[n], m.file(), m.path("controls") + "/" + std::to_string(n));
      HeightfieldMaskingControl ctl;
      ctl.g2 = c.one_of("g", {"g1", "g2"}) == "g2";
      ctl.model = ctl.g2 ? c.one_of("model", {"smith_separable", "smith_height_correlated",
                                              "smith_height_direction_correlated", "vcavity"})
                         : c.one_of("model", {"smith", "vcavity"});
      const std::string ndf = c.one_of("ndf", {"beckmann", "ggx"});
      const double alpha = c.number("alpha", kMinAlpha, true, kMaxAlpha, true);
      const double theta_i = c.number("theta_i_deg", 0.0, true, kMaxSurfaceThetaIDeg, true);
      const double theta_o = c.number("theta_o_deg", 0.0, true, kMaxSurfaceThetaIDeg, true);
      const double phi = ctl.g2 ? c.number("phi_deg", 0.0, true, 180.0, true) : 0.0;
      ctl.every_bin = c.boolean_or("every_bin", false);
      c.finish();
      bool found = false;
      for (std::size_t k = 0; k < suite.cases() && !found; ++k) {
        const HeightfieldCase hc = suite.case_at(k);
        if (analytic::ndf_name(hc.ndf) == ndf && hc.alpha == alpha && hc.theta_i_deg == theta_i)
          ctl.case_index = k, found = true;
      }
      if (!found)
        m.fail_at("controls", n,
                  "names no case of the suite (ndf " + ndf + ", alpha " + support::number_text(alpha) +
                      ", theta_i_deg " + support::number_text(theta_i) + "): a control must be one of its cases");
      const auto at = [](const std::vector<double>& v, double x) {
        return static_cast<std::size_t>(std::find(v.begin(), v.end(), x) - v.begin());
      };
      ctl.theta_o_index = at(s.theta_o_deg, theta_o), ctl.phi_index = at(s.phi_deg, phi);
      if (ctl.theta_o_index == s.theta_o_deg.size())
        m.fail_at("controls", n, "theta_o_deg " + support::number_text(theta_o) + " is not one of masking/theta_o_deg");
      if (ctl.g2 && ctl.phi_index == s.phi_deg.size())
        m.fail_at("controls", n, "phi_deg " + support::number_text(phi) + " is not one of masking/phi_deg");
      s.controls.push_back(ctl);
    }
  }
  m.finish();
  return s;
}

const HeightfieldMaskingMiss* masking_control_miss(const HeightfieldMaskingControl& c, const HeightfieldOutcome& o) {
  if (o.g1.empty()) return nullptr;  // not measured (interrupted)
  const std::size_t item = c.g2 ? c.theta_o_index * (o.g2.size() / o.g1.size()) + c.phi_index : c.theta_o_index;
  const std::vector<HeightfieldMaskingValue>& list = c.g2 ? o.g2 : o.g1;
  if (item >= list.size()) return nullptr;
  for (const HeightfieldMaskingMiss& m : list[item].models)
    if (m.model == c.model) return &m;
  return nullptr;
}

bool masking_control_holds(const HeightfieldMaskingControl& c, const HeightfieldOutcome& o) {
  const HeightfieldMaskingMiss* m = masking_control_miss(c, o);
  return m != nullptr && (c.every_bin ? m->within_noise : m->overall_within_noise);
}

namespace {

struct ControlText {
  HeightfieldCase c;
  double theta_o = 0.0, phi = 0.0;
};
ControlText control_text(const HeightfieldSuite& suite, const HeightfieldMaskingControl& ctl) {
  return {suite.case_at(ctl.case_index), suite.masking->theta_o_deg[ctl.theta_o_index],
          ctl.g2 ? suite.masking->phi_deg[ctl.phi_index] : 0.0};
}

}  // namespace

nlohmann::json masking_controls_json(const HeightfieldSuite& suite, const HeightfieldRun& run) {
  nlohmann::json out = nlohmann::json::array();
  if (!suite.masking) return out;
  for (std::size_t n = 0; n < suite.masking->controls.size(); ++n) {
    const HeightfieldMaskingControl& ctl = suite.masking->controls[n];
    const ControlText t = control_text(suite, ctl);
    nlohmann::json j = {{"g", ctl.g2 ? "g2" : "g1"},
                        {"model", ctl.model},
                        {"ndf", analytic::ndf_name(t.c.ndf)},
                        {"alpha", t.c.alpha},
                        {"theta_i_deg", t.c.theta_i_deg},
                        {"theta_o_deg", t.theta_o},
                        {"every_bin", ctl.every_bin},
                        {"within_noise", n < run.masking_controls_hold.size() && run.masking_controls_hold[n]}};
    if (ctl.g2) j["phi_deg"] = t.phi;
    if (ctl.case_index < run.cases.size())
      if (const HeightfieldMaskingMiss* m = masking_control_miss(ctl, run.cases[ctl.case_index])) {
        j["traced"] = m->value + m->diff;
        j["model_value"] = m->value;
        j["z"] = m->z;
        j["worst_bin"] = m->worst_bin;
        j["worst_bin_z"] = m->worst_bin_z;
      }
    out.push_back(std::move(j));
  }
  return out;
}

void print_masking_controls(std::ostream& os, const HeightfieldSuite& suite, const HeightfieldRun& run) {
  if (!suite.masking) return;
  for (std::size_t n = 0; n < suite.masking->controls.size(); ++n) {
    const HeightfieldMaskingControl& ctl = suite.masking->controls[n];
    const ControlText t = control_text(suite, ctl);
    const bool held = n < run.masking_controls_hold.size() && run.masking_controls_hold[n];
    std::string where =
        support::format("%s %s on %s alpha %.2f theta_i %.1f theta_o %.1f", ctl.g2 ? "G2" : "G1", ctl.model.c_str(),
                        analytic::ndf_name(t.c.ndf), t.c.alpha, t.c.theta_i_deg, t.theta_o);
    if (ctl.g2) where += support::format(" dphi %.1f", t.phi);
    where += ctl.every_bin ? ", overall and every bin" : ", overall";
    std::string how;
    if (ctl.case_index < run.cases.size())
      if (const HeightfieldMaskingMiss* m = masking_control_miss(ctl, run.cases[ctl.case_index])) {
        how = support::format(" (%.1f se", std::abs(m->z));
        if (ctl.every_bin && m->worst_bin >= 0)
          how += support::format("; worst bin %d, %.1f se", m->worst_bin, std::abs(m->worst_bin_z));
        how += ")";
      }
    os << "  masking control: " << where << ": " << (held ? "within noise" : "NOT within noise (fails the suite)")
       << how << "\n";
  }
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
      const double phi_ref = sim::heightfield_joint_bin_azimuth(theta_i, 0.0, theta_o, phi_o);
      for (int b = 0; b < bins; ++b)
        vb.push_back(
            analytic::vcavity_g2_bin_average(ndf, alpha, theta_i, 0.0, theta_o, phi_o, normal_bin(m, b, phi_ref)));
      v.models.push_back(heightfield_masking_miss(
          "vcavity", v, analytic::vcavity_g2_bin_average(ndf, alpha, theta_i, 0.0, theta_o, phi_o, all), vb, sig, tol));
      out.g2.push_back(std::move(v));
    }
}

}  // namespace vgroove::validation
