// vgroove validation: the energy audit's figures, report and table (energy_audit.h).
#include "vgroove/validation/energy_audit.h"

#include "vgroove/support/format.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/table_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace vgroove::validation {

// ---- Colour ---------------------------------------------------------------------------------------

void lab_from_linear_srgb(const double rgb[3], double lab[3]) {
  // IEC 61966-2-1: linear sRGB to XYZ (D65), and the D65 white point (Y = 1).
  const double X = 0.4124564 * rgb[0] + 0.3575761 * rgb[1] + 0.1804375 * rgb[2];
  const double Y = 0.2126729 * rgb[0] + 0.7151522 * rgb[1] + 0.0721750 * rgb[2];
  const double Z = 0.0193339 * rgb[0] + 0.1191920 * rgb[1] + 0.9503041 * rgb[2];
  const double Xn = 0.95047, Yn = 1.0, Zn = 1.08883;
  // CIE 1976 L*a*b*: f(t) = t^(1/3) above (6/29)^3, linear below.
  auto f = [](double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
  };
  const double fx = f(X / Xn), fy = f(Y / Yn), fz = f(Z / Zn);
  lab[0] = 116.0 * fy - 16.0;
  lab[1] = 500.0 * (fx - fy);
  lab[2] = 200.0 * (fy - fz);
}

double delta_e_2000(const double lab1[3], const double lab2[3]) {
  // Sharma, Wu, Dalal, "The CIEDE2000 color-difference formula: implementation notes,
  // supplementary test data, and mathematical observations", Color Res. Appl. 30(1), 2005,
  // Eq. (1)-(22); angles in degrees as there, k_L = k_C = k_H = 1.
  constexpr double kDeg = std::numbers::pi / 180.0;
  const double L1 = lab1[0], a1 = lab1[1], b1 = lab1[2], L2 = lab2[0], a2 = lab2[1], b2 = lab2[2];
  const double C1 = std::hypot(a1, b1), C2 = std::hypot(a2, b2), Cbar = 0.5 * (C1 + C2);
  const double Cbar7 = std::pow(Cbar, 7.0), p25 = std::pow(25.0, 7.0);
  const double G = 0.5 * (1.0 - std::sqrt(Cbar7 / (Cbar7 + p25)));    // Eq. (4)
  const double a1p = (1.0 + G) * a1, a2p = (1.0 + G) * a2;            // Eq. (5)
  const double C1p = std::hypot(a1p, b1), C2p = std::hypot(a2p, b2);  // Eq. (6)
  auto hue = [&](double b, double ap) {                               // Eq. (7)
    if (b == 0.0 && ap == 0.0) return 0.0;
    const double h = std::atan2(b, ap) / kDeg;
    return h < 0.0 ? h + 360.0 : h;
  };
  const double h1p = hue(b1, a1p), h2p = hue(b2, a2p);
  const double dLp = L2 - L1, dCp = C2p - C1p;  // Eq. (8), (9)
  double dhp = 0.0;                             // Eq. (10)
  if (C1p * C2p != 0.0) {
    dhp = h2p - h1p;
    if (dhp > 180.0) dhp -= 360.0;
    if (dhp < -180.0) dhp += 360.0;
  }
  const double dHp = 2.0 * std::sqrt(C1p * C2p) * std::sin(0.5 * dhp * kDeg);  // Eq. (11)
  const double Lbp = 0.5 * (L1 + L2), Cbp = 0.5 * (C1p + C2p);                 // Eq. (12), (13)
  double hbp = h1p + h2p;                                                      // Eq. (14)
  if (C1p * C2p != 0.0) {
    if (std::abs(h1p - h2p) <= 180.0)
      hbp = 0.5 * (h1p + h2p);
    else
      hbp = h1p + h2p < 360.0 ? 0.5 * (h1p + h2p + 360.0) : 0.5 * (h1p + h2p - 360.0);
  }
  const double T = 1.0 - 0.17 * std::cos((hbp - 30.0) * kDeg) + 0.24 * std::cos(2.0 * hbp * kDeg) +
                   0.32 * std::cos((3.0 * hbp + 6.0) * kDeg) - 0.20 * std::cos((4.0 * hbp - 63.0) * kDeg);  // (15)
  const double dtheta = 30.0 * std::exp(-std::pow((hbp - 275.0) / 25.0, 2.0));                              // Eq. (16)
  const double Cbp7 = std::pow(Cbp, 7.0);
  const double RC = 2.0 * std::sqrt(Cbp7 / (Cbp7 + p25));  // Eq. (17)
  const double l50 = (Lbp - 50.0) * (Lbp - 50.0);
  const double SL = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);      // Eq. (18)
  const double SC = 1.0 + 0.045 * Cbp, SH = 1.0 + 0.015 * Cbp * T;  // Eq. (19), (20)
  const double RT = -std::sin(2.0 * dtheta * kDeg) * RC;            // Eq. (21)
  const double l = dLp / SL, c = dCp / SC, h = dHp / SH;
  return std::sqrt(l * l + c * c + h * h + RT * c * h);  // Eq. (22)
}

double delta_e_2000_linear_srgb(const double rgb_a[3], const double rgb_b[3]) {
  double la[3], lb[3];
  lab_from_linear_srgb(rgb_a, la);
  lab_from_linear_srgb(rgb_b, lb);
  return delta_e_2000(la, lb);
}

// ---- Figures --------------------------------------------------------------------------------------

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kEnergyUnit = 4294967296.0;
const char* const kRegions[] = {"all", "rough", "grazing"};
const char* const kGroups[] = {"grey",         "conductor",        "metal_schlick",
                               "engine_metal", "metalness_before", "metalness_after"};
constexpr int kRefs = 3, kNumRegions = 3, kNumGroups = 6;
constexpr int kHeightfield = 2;  // the optional reference (EnergyAuditSuite::heightfield)

// Worst, mean |.| and mean of a set of errors, with where the worst is.
struct Stat {
  double worst = 0.0, worst_signed = 0.0, sum_abs = 0.0, sum = 0.0;
  long n = 0;
  std::string at;
  void add(double e, const std::function<std::string()>& where) {
    if (!std::isfinite(e)) return;
    ++n, sum_abs += std::abs(e), sum += e;
    if (std::abs(e) > worst || n == 1) worst = std::abs(e), worst_signed = e, at = where();
  }
  double mean_abs() const { return n ? sum_abs / n : kNaN; }
  nlohmann::json json() const {
    if (n == 0) return nullptr;
    return {{"worst", exact_json(worst_signed)},
            {"mean_abs", exact_json(sum_abs / n)},
            {"mean", exact_json(sum / n)},
            {"count", n},
            {"at", at}};
  }
};

bool in_region(int region, const EnergyAuditSuite& s, const EnergyAuditCell& c) {
  return region == 0 || (region == 1 && c.alpha >= s.rough_alpha) || (region == 2 && c.mu <= s.grazing_mu);
}

std::string cell_text(const EnergyAuditCell& c) {
  return support::format("%s alpha %.4g mu %.4g", ndf_name(c.ndf), c.alpha, c.mu);
}

struct CellData {
  EnergyAuditCell cell;
  std::vector<double> E[kRefs], se[kRefs], rows[kRefs];  // [c], [c], [row * C + c]
  const SingleScattering* ss[kRefs] = {nullptr, nullptr, nullptr};
  SingleScattering ss_avg[kRefs];  // with the E_avg of its alpha
  const std::vector<double>* E_F[kRefs] = {nullptr, nullptr, nullptr};
  const AuditFixed* fixed = nullptr;  // its separable single scattering: the moonray_table feed's lobe
  EngineValues engine{kNaN, kNaN, kNaN, {}};
  std::vector<std::vector<double>> A[kRefs];  // [variant][c]
};

// The feeds a reference's formulas take: engine tables against the walk and the heightfields
// (both fed with Smith's single scattering) for GGX only.
// The engines' tables are made for Smith's microsurface (not the V-groove reference's V-cavity one);
// MoonRay's for GGX and Beckmann up to alpha 1, the others' for GGX.
bool variant_applies(const FormulaVariant& v, int ref, NdfKind ndf, double alpha) {
  if (v.feed == Feed::exact) return true;
  if (ref == 0) return false;
  if (v.feed == Feed::moonray_table) return alpha <= 1.0;
  return ndf == NdfKind::ggx;
}

// The references a suite audits: the V-groove model and the walk always, the heightfields opt-in.
bool audited(const EnergyAuditSuite& s, int ref) { return ref != kHeightfield || s.heightfield; }

nlohmann::json nested(const std::vector<double>& v, const std::vector<std::size_t>& shape, std::size_t dim = 0,
                      std::size_t offset = 0) {
  nlohmann::json out = nlohmann::json::array();
  std::size_t stride = 1;
  for (std::size_t d = dim + 1; d < shape.size(); ++d) stride *= shape[d];
  for (std::size_t i = 0; i < shape[dim]; ++i)
    out.push_back(dim + 1 == shape.size() ? exact_json(v[offset + i]) : nested(v, shape, dim + 1, offset + i * stride));
  return out;
}

}  // namespace

EnergyAuditRun energy_audit_run_from(const EnergyAuditSuite& s, const std::vector<UnitResult<EnergyAuditWork>>& r) {
  EnergyAuditRun run;
  run.cells = r;
  const ChannelSet channels(s.grey_F0, s.metals);
  const int C = channels.size(), R = s.max_k + 2;
  const std::vector<FormulaVariant>& variants = formula_variants();
  const int V = static_cast<int>(variants.size());
  const int white = channels.find_grey(1.0), dielectric = channels.find_grey(0.04);

  // The references and the formulas per cell.
  std::vector<CellData> cells(r.size());
  double model_s = 0.0;
  for (std::size_t n = 0; n < r.size(); ++n) {
    CellData& d = cells[n];
    d.cell = s.cell_at(n);
    const AuditFixed& f = *r[n].fixed;
    const AuditTally& t = r[n].tally;
    model_s += f.seconds;
    const AuditFixed& avg = *r[n - d.cell.mu_index].fixed;  // E_avg lives at the cell of mu index 0
    // vgroove: the model's rows; the formulas on the V-cavity model.
    d.rows[0] = f.vgroove_rows;
    d.E[0].assign(C, 0.0), d.se[0].assign(C, 0.0);
    for (int k = 0; k < R; ++k)
      for (int c = 0; c < C; ++c) d.E[0][c] += f.vgroove_rows[static_cast<std::size_t>(k) * C + c];
    d.fixed = &f;
    d.ss_avg[0] = f.vcavity, d.ss_avg[0].E_avg = avg.vcavity.E_avg, d.E_F[0] = &f.vcavity_E_F;
    // smith_walk: energy per path; the formulas on Smith's height-correlated model.
    const double N = static_cast<double>(t.paths);
    d.rows[1].assign(static_cast<std::size_t>(R) * C, 0.0);
    d.E[1].assign(C, 0.0), d.se[1].assign(C, 0.0);
    for (int k = 0; k < R; ++k)
      for (int c = 0; c < C; ++c) {
        const double e = static_cast<double>(t.energy[static_cast<std::size_t>(k) * C + c]) / kEnergyUnit / N;
        d.rows[1][static_cast<std::size_t>(k) * C + c] = e;
        d.E[1][c] += e;
      }
    for (int c = 0; c < C; ++c) d.se[1][c] = std::sqrt(std::max(0.0, d.E[1][c] * (1.0 - d.E[1][c])) / N);
    d.ss_avg[1] = f.smith, d.ss_avg[1].E_avg = avg.smith.E_avg, d.E_F[1] = &f.smith_E_F;
    // heightfield: energy per ray; the formulas on Smith's height-correlated model (what engines
    // fit to: the question is how far a surface is from it), E_1 a measured result beside it.
    if (s.heightfield) {
      const double M = static_cast<double>(t.hf_rays);
      d.rows[2].assign(static_cast<std::size_t>(R) * C, 0.0);
      d.E[2].assign(C, 0.0), d.se[2].assign(C, 0.0);
      std::vector<std::int64_t> units(static_cast<std::size_t>(C), 0);
      for (int k = 0; k < R; ++k)
        for (int c = 0; c < C; ++c) {
          const std::int64_t u = t.hf_energy[static_cast<std::size_t>(k) * C + c];
          d.rows[2][static_cast<std::size_t>(k) * C + c] = static_cast<double>(u) / kEnergyUnit / M;
          units[static_cast<std::size_t>(c)] += u;
        }
      // The total from the integers: the white channel is 1 to the bit when every ray left.
      for (int c = 0; c < C; ++c) d.E[2][c] = static_cast<double>(units[static_cast<std::size_t>(c)]) / kEnergyUnit / M;
      // Standard error: the fields' spread, at least the rays' (heightfield_albedo.h's rule).
      const double nf = s.hf_fields, per_field = M / nf;
      for (int c = 0; c < C; ++c) {
        double var = 0.0;
        for (int fi = 0; fi < s.hf_fields; ++fi) {
          const double x =
              static_cast<double>(t.hf_field_energy[static_cast<std::size_t>(fi) * C + c]) / kEnergyUnit / per_field -
              d.E[2][c];
          var += x * x;
        }
        const double q = std::clamp(d.E[2][c], 0.0, 1.0);
        d.se[2][c] =
            std::max(nf >= 2 ? std::sqrt(var / (nf - 1.0) / nf) : 0.0, std::sqrt(std::max(q * (1.0 - q), 1.0 / M) / M));
      }
      d.ss_avg[2] = d.ss_avg[1], d.E_F[2] = &f.smith_E_F;
    }
    d.engine = {f.cycles_E, f.cycles_E_avg, f.filament_dfg_y,
                analytic::karis_env_brdf_approx(std::min(1.0, std::sqrt(d.cell.alpha)), d.cell.mu)};
    if (d.cell.alpha <= 1.0) {  // MoonRay's tables end at roughness 1
      const MoonrayTables& m = published_moonray_tables();
      d.engine.moonray_E = moonray_E(m, d.cell.ndf, d.cell.alpha, d.cell.mu);
      d.engine.moonray_one_minus_E_avg = moonray_one_minus_E_avg(m, d.cell.ndf, d.cell.alpha);
      d.engine.moonray_missing_average = moonray_missing_average(m, d.cell.ndf, d.cell.alpha);
      d.engine.moonray_compensates = moonray_compensates(d.cell.alpha);
    }
    for (int ref = 0; ref < kRefs; ++ref) {
      d.A[ref].assign(V, std::vector<double>(C, kNaN));
      if (!audited(s, ref)) continue;
      for (int v = 0; v < V; ++v) {
        if (!variant_applies(variants[v], ref, d.cell.ndf, d.cell.alpha)) continue;
        for (int c = 0; c < C; ++c) {
          // MoonRay's lobes have Smith's separable G2: its feed's single scattering is that one.
          const std::vector<double>& E_F =
              variants[v].feed == Feed::moonray_table ? d.fixed->separable_E_F : *d.E_F[ref];
          const ChannelValues cv{channels.channels()[c].F0, channels.F_avg(c), E_F[c]};
          d.A[ref][v][c] = compensated_albedo(variants[v], d.ss_avg[ref], d.engine, cv, d.cell.alpha, d.cell.mu);
        }
      }
    }
  }

  // The errors per variant, reference, group and region.
  std::vector<Stat> stats(static_cast<std::size_t>(V) * kRefs * kNumGroups * kNumRegions);
  auto stat = [&](int v, int ref, int g, int reg) -> Stat& {
    return stats[((static_cast<std::size_t>(v) * kRefs + ref) * kNumGroups + g) * kNumRegions + reg];
  };
  std::vector<double> errors(static_cast<std::size_t>(V) * kRefs * r.size() * C, kNaN);
  for (std::size_t n = 0; n < cells.size(); ++n) {
    const CellData& d = cells[n];
    for (int ref = 0; ref < kRefs; ++ref)
      for (int v = 0; v < V; ++v) {
        if (!audited(s, ref) || !variant_applies(variants[v], ref, d.cell.ndf, d.cell.alpha)) continue;
        auto add = [&](int g, double e, const std::string& what) {
          for (int reg = 0; reg < kNumRegions; ++reg)
            if (in_region(reg, s, d.cell)) stat(v, ref, g, reg).add(e, [&] { return cell_text(d.cell) + ", " + what; });
        };
        for (int c = 0; c < C; ++c) {
          const Channel& ch = channels.channels()[c];
          const double e = d.A[ref][v][c] - d.E[ref][c];
          errors[((static_cast<std::size_t>(v) * kRefs + ref) * r.size() + n) * C + c] = e;
          add(ch.group == "grey" ? 0 : ch.group == "conductor" ? 1 : 2, e, ch.name);
        }
        for (const std::string& metal : s.metals)
          for (int b = 0; b < 3; ++b) {
            const int sc = channels.find("metal_schlick", metal, b), cc = channels.find("conductor", metal, b);
            const Channel& ch = channels.channels()[sc];
            add(3, d.A[ref][v][sc] - d.E[ref][cc], channels.channels()[cc].name + " given Schlick F0");
            for (double m : s.metalness) {
              const double exact = (1.0 - m) * d.E[ref][dielectric] + m * d.E[ref][sc];
              const double F0 = (1.0 - m) * 0.04 + m * ch.F0;
              const SingleScattering& lobe =
                  variants[v].feed == Feed::moonray_table ? d.fixed->separable : d.ss_avg[ref];
              const ChannelValues cv{F0, F0 + (1.0 - F0) / 21.0, F0 * lobe.scale + lobe.bias};
              const double before =
                  compensated_albedo(variants[v], d.ss_avg[ref], d.engine, cv, d.cell.alpha, d.cell.mu);
              const double after = (1.0 - m) * d.A[ref][v][dielectric] + m * d.A[ref][v][sc];
              const std::string what = metal + " band " + std::to_string(b) + " metalness " + support::number_text(m);
              add(4, before - exact, what);
              add(5, after - exact, what);
            }
          }
      }
  }

  // The colour shift of Au and Cu.
  nlohmann::json colour = nlohmann::json::object();
  for (const std::string& metal : {std::string("Au"), std::string("Cu")}) {
    if (std::find(s.metals.begin(), s.metals.end(), metal) == s.metals.end()) continue;
    for (int ref = 0; ref < kRefs; ++ref)
      for (int v = 0; v < V; ++v)
        for (const std::string& given : {std::string("conductor"), std::string("metal_schlick")}) {
          if (!audited(s, ref)) continue;
          Stat dE[kNumRegions], ratio[kNumRegions][3];
          bool any = false;
          for (const CellData& d : cells) {
            if (!variant_applies(variants[v], ref, d.cell.ndf, d.cell.alpha)) continue;
            double got[3], want[3];
            for (int b = 0; b < 3; ++b) {
              // R, G, B = bands 2, 1, 0 (~650, ~550, ~450 nm).
              got[2 - b] = d.A[ref][v][channels.find(given, metal, b)];
              want[2 - b] = d.E[ref][channels.find("conductor", metal, b)];
            }
            const double e = delta_e_2000_linear_srgb(got, want);
            any = true;
            for (int reg = 0; reg < kNumRegions; ++reg) {
              if (!in_region(reg, s, d.cell)) continue;
              dE[reg].add(e, [&] { return cell_text(d.cell); });
              for (int q = 0; q < 3; ++q) ratio[reg][q].add(got[q] / want[q] - 1.0, [&] { return cell_text(d.cell); });
            }
          }
          if (!any) continue;
          nlohmann::json j;
          for (int reg = 0; reg < kNumRegions; ++reg)
            j[kRegions[reg]] = {
                {"delta_e_2000", dE[reg].json()},
                {"ratio_minus_1",
                 {{"R", ratio[reg][0].json()}, {"G", ratio[reg][1].json()}, {"B", ratio[reg][2].json()}}}};
          colour[metal][given == "conductor" ? "conductor" : "engine_schlick"][kAuditReferences[ref]][variants[v].id] =
              j;
        }
  }

  // The references' checks: the verdict.
  double walk_white = 0.0, walk_z = 0.0, vg_white = 0.0, vg_single = 0.0;
  std::int64_t lost = 0;
  std::string walk_z_at, vg_white_at, vg_single_at;
  for (std::size_t n = 0; n < cells.size(); ++n) {
    const CellData& d = cells[n];
    const AuditTally& t = r[n].tally;
    const AuditFixed& f = *r[n].fixed;
    lost += t.lost;
    // In integers: every path that left carries exactly 2^32 units in the white channel.
    std::int64_t units = 0;
    for (int k = 0; k < R; ++k) units += t.energy[static_cast<std::size_t>(k) * C + white];
    walk_white =
        std::max(walk_white, std::abs(static_cast<double>(units) / kEnergyUnit - static_cast<double>(t.paths)) /
                                 static_cast<double>(t.paths));
    const double N = static_cast<double>(t.paths), p = f.smith.E;
    const double E1 = static_cast<double>(t.by_k[1]) / N;
    const double z = std::abs(E1 - p) / (std::sqrt(std::max(0.0, p * (1.0 - p)) / N) + 1.0 / N);
    if (z > walk_z || std::isnan(z)) walk_z = z, walk_z_at = cell_text(d.cell);
    const double w = std::abs(d.E[0][white] - 1.0);
    if (w > vg_white) vg_white = w, vg_white_at = cell_text(d.cell);
    const double g = std::abs(f.vgroove_rows[static_cast<std::size_t>(C) + white] - f.vcavity.E);
    if (g > vg_single) vg_single = g, vg_single_at = cell_text(d.cell);
  }
  // The heightfields: every ray leaves, so the white channel is 1 exactly (a check); E_1 against
  // Smith's E_ss in standard errors (a measured result: the fields are not Smith's surface).
  double hf_white = 0.0, hf_z = 0.0, hf_d1 = 0.0;
  std::int64_t hf_lost = 0, hf_limit = 0;
  std::string hf_z_at;
  std::vector<double> hf_E1_minus_ess, hf_E1_se;
  if (s.heightfield)
    for (std::size_t n = 0; n < cells.size(); ++n) {
      const AuditTally& t = r[n].tally;
      const AuditFixed& f = *r[n].fixed;
      hf_lost += t.hf_lost, hf_limit += t.hf_bounce_limit;
      std::int64_t units = 0;
      for (int k = 0; k < R; ++k) units += t.hf_energy[static_cast<std::size_t>(k) * C + white];
      hf_white =
          std::max(hf_white, std::abs(static_cast<double>(units) / kEnergyUnit - static_cast<double>(t.hf_rays)) /
                                 static_cast<double>(t.hf_rays));
      const double M = static_cast<double>(t.hf_rays), nf = s.hf_fields, per_field = M / nf;
      const double E1 = static_cast<double>(t.hf_by_k[1]) / M;
      double var = 0.0;
      for (int fi = 0; fi < s.hf_fields; ++fi) {
        const double x = static_cast<double>(t.hf_field_by_k[static_cast<std::size_t>(fi) * R + 1]) / per_field - E1;
        var += x * x;
      }
      const double q = std::clamp(E1, 0.0, 1.0);
      const double se =
          std::max(nf >= 2 ? std::sqrt(var / (nf - 1.0) / nf) : 0.0, std::sqrt(std::max(q * (1.0 - q), 1.0 / M) / M));
      hf_E1_minus_ess.push_back(E1 - f.smith.E), hf_E1_se.push_back(se);
      const double z = std::abs(E1 - f.smith.E) / se;
      if (z > hf_z || std::isnan(z)) hf_z = z, hf_z_at = cell_text(cells[n].cell), hf_d1 = E1 - f.smith.E;
    }
  const bool hf_ok = hf_lost == 0 && hf_limit == 0 && hf_white == 0.0;
  const bool walk_ok = lost == 0 && walk_white == 0.0, z_ok = walk_z <= s.sigmas;
  const bool vg_ok = vg_white <= s.vgroove_furnace, vg1_ok = vg_single <= s.vgroove_furnace;
  run.pass = walk_ok && z_ok && vg_ok && vg1_ok && hf_ok;

  // Which formula is closest where (the mean |error| among the compensations, "single" aside).
  nlohmann::json closest = nlohmann::json::array();
  std::vector<std::string> statements;
  for (int ref = 0; ref < kRefs; ++ref)
    for (int g : audited(s, ref) ? std::vector<int>{0, 1, 3, 4, 5} : std::vector<int>{})
      for (int reg = 0; reg < kNumRegions; ++reg) {
        int best = -1, worst = -1;
        for (int v = 1; v < V; ++v) {
          const Stat& st = stat(v, ref, g, reg);
          if (st.n == 0) continue;
          if (best < 0 || st.mean_abs() < stat(best, ref, g, reg).mean_abs()) best = v;
          if (worst < 0 || st.mean_abs() > stat(worst, ref, g, reg).mean_abs()) worst = v;
        }
        if (best < 0) continue;
        const Stat &b = stat(best, ref, g, reg), &w = stat(worst, ref, g, reg), &none = stat(0, ref, g, reg);
        closest.push_back({{"reference", kAuditReferences[ref]},
                           {"group", kGroups[g]},
                           {"region", kRegions[reg]},
                           {"closest", variants[best].id},
                           {"mean_abs", exact_json(b.mean_abs())},
                           {"worst", exact_json(b.worst_signed)},
                           {"farthest", variants[worst].id},
                           {"farthest_mean_abs", exact_json(w.mean_abs())},
                           {"uncompensated_mean_abs", exact_json(none.mean_abs())}});
        statements.push_back(support::format(
            "against %s, %s, %s: closest %s (mean |error| %.2e, worst %+.2e at %s); farthest %s (%.2e); no "
            "compensation %.2e",
            kAuditReferences[ref], kGroups[g], kRegions[reg], variants[best].id.c_str(), b.mean_abs(), b.worst_signed,
            b.at.c_str(), variants[worst].id.c_str(), w.mean_abs(), none.mean_abs()));
      }

  // The body of the report.
  nlohmann::json& j = run.body;
  nlohmann::json ch = nlohmann::json::array();
  for (const Channel& c : channels.channels()) {
    nlohmann::json x = {{"name", c.name}, {"group", c.group}, {"F0", exact_json(c.F0)}};
    if (c.kind == ChannelKind::conductor) x["eta"] = c.eta, x["kappa"] = c.kappa;
    if (!c.metal.empty()) x["metal"] = c.metal, x["band"] = c.band;
    x["F_avg"] = exact_json(channels.F_avg(static_cast<int>(&c - channels.channels().data())));
    ch.push_back(x);
  }
  j["channels"] = ch;
  nlohmann::json vs = nlohmann::json::array();
  for (const FormulaVariant& v : variants)
    vs.push_back({{"id", v.id}, {"formula", v.formula}, {"feed", feed_name(v.feed)}, {"source", v.source}});
  j["variants"] = vs;
  j["regions"] = {{"rough", "alpha >= " + support::number_text(s.rough_alpha)},
                  {"grazing", "mu <= " + support::number_text(s.grazing_mu)}};
  j["colour_space"] =
      "the three bands of a metal (~650, ~550, ~450 nm) read as linear sRGB R, G, B (an assumption, not a spectral "
      "integration), to CIE L*a*b* with the D65 white; CIE Delta E 2000 (Sharma et al. 2005)";
  const std::vector<std::size_t> cell_shape = {s.ndfs.size(), s.alphas.size(), s.mus.size(),
                                               static_cast<std::size_t>(C)};
  std::vector<std::size_t> row_shape = {s.ndfs.size(), s.alphas.size(), s.mus.size(), static_cast<std::size_t>(R),
                                        static_cast<std::size_t>(C)};
  nlohmann::json refs;
  for (int ref = 0; ref < kRefs; ++ref) {
    if (!audited(s, ref)) continue;
    std::vector<double> E, se, rows;
    for (const CellData& d : cells) {
      E.insert(E.end(), d.E[ref].begin(), d.E[ref].end());
      se.insert(se.end(), d.se[ref].begin(), d.se[ref].end());
      rows.insert(rows.end(), d.rows[ref].begin(), d.rows[ref].end());
    }
    refs[kAuditReferences[ref]] = {{"E", nested(E, cell_shape)}, {"E_by_k", nested(rows, row_shape)}};
    if (ref != 0) refs[kAuditReferences[ref]]["se"] = nested(se, cell_shape);
  }
  if (s.heightfield) {
    const std::vector<std::size_t> shape = {s.ndfs.size(), s.alphas.size(), s.mus.size()};
    refs["heightfield"]["E1_minus_smith_E_ss"] = nested(hf_E1_minus_ess, shape);
    refs["heightfield"]["E1_se"] = nested(hf_E1_se, shape);
    refs["heightfield"]["formulas_fed_with"] =
        "Smith's height-correlated single scattering (E_ss, E_avg, split sum), as against the walk: the formulas "
        "engines ship, held against a surface; the fields' own E_1 is a measured result beside it";
  }
  j["references"] = refs;
  {
    nlohmann::json single;
    std::vector<double> a[8];
    for (std::size_t n = 0; n < cells.size(); ++n) {
      const AuditFixed& f = *r[n].fixed;
      const CellData& d = cells[n];
      a[0].push_back(f.smith.E), a[1].push_back(f.smith.scale), a[2].push_back(f.smith.bias);
      a[3].push_back(d.ss_avg[1].E_avg), a[4].push_back(f.vcavity.E), a[5].push_back(d.ss_avg[0].E_avg);
      a[6].push_back(f.filament_dfg_y), a[7].push_back(f.cycles_E);
    }
    const std::vector<std::size_t> shape = {s.ndfs.size(), s.alphas.size(), s.mus.size()};
    const char* names[] = {"smith_E",   "smith_scale",   "smith_bias",     "smith_E_avg",
                           "vcavity_E", "vcavity_E_avg", "filament_dfg_y", "cycles_E"};
    for (int q = 0; q < 8; ++q) single[names[q]] = nested(a[q], shape);
    j["single_scattering"] = single;
  }
  nlohmann::json err, summary;
  for (int v = 0; v < V; ++v)
    for (int ref = 0; ref < kRefs; ++ref) {
      const std::vector<double> part(
          errors.begin() + static_cast<std::ptrdiff_t>((v * kRefs + ref) * r.size() * C),
          errors.begin() + static_cast<std::ptrdiff_t>((v * kRefs + ref + 1) * r.size() * C));
      if (std::all_of(part.begin(), part.end(), [](double x) { return std::isnan(x); })) continue;
      err[variants[v].id][kAuditReferences[ref]] = nested(part, cell_shape);
      for (int g = 0; g < kNumGroups; ++g)
        for (int reg = 0; reg < kNumRegions; ++reg)
          summary[variants[v].id][kAuditReferences[ref]][kGroups[g]][kRegions[reg]] = stat(v, ref, g, reg).json();
    }
  j["errors"] = err;
  j["summary"] = summary;
  j["colour_shift"] = colour;
  j["closest"] = closest;
  j["statement"] = statements;
  j["checks"] = {
      {"walk_white_furnace",
       {{"pass", walk_ok},
        {"largest_deviation", exact_json(walk_white)},
        {"lost_paths", lost},
        {"what", "F = 1: every path leaves, so the white channel's albedo is 1 exactly"}}},
      {"walk_single_scattering",
       {{"pass", z_ok},
        {"largest_z", exact_json(walk_z)},
        {"at", walk_z_at},
        {"sigmas", s.sigmas},
        {"what", "E_1 of the walk against Smith's height-correlated E_ss by quadrature, in standard errors"}}},
      {"vgroove_white_furnace",
       {{"pass", vg_ok},
        {"largest_deviation", exact_json(vg_white)},
        {"at", vg_white_at},
        {"tolerance", s.vgroove_furnace}}},
      {"vgroove_single_scattering",
       {{"pass", vg1_ok},
        {"largest_deviation", exact_json(vg_single)},
        {"at", vg_single_at},
        {"tolerance", s.vgroove_furnace},
        {"what", "the model's first row against the V-cavity E_ss by quadrature (Cook-Torrance's albedo)"}}}};
  if (s.heightfield) {
    j["checks"]["heightfield_white_furnace"] = {
        {"pass", hf_ok},
        {"largest_deviation", exact_json(hf_white)},
        {"lost_rays", hf_lost},
        {"bounce_limit_rays", hf_limit},
        {"what", "F = 1: every ray leaves the field, so the white channel's albedo is 1 exactly"}};
    j["heightfield_single_scattering"] = {
        {"largest_z", exact_json(hf_z)},
        {"at", hf_z_at},
        {"E1_minus_smith_E_ss_there", exact_json(hf_d1)},
        {"what",
         "a measured result, not a check: the fields' E_1 against Smith's height-correlated E_ss by quadrature, in "
         "standard errors (the fields' spread); the fields are not Smith's surface"}};
  }
  j["lobe_shape"] =
      "not measured: the compensated lobes against the traced lobes by the Fig. 11 metric are not part of this audit";
  j["references_left_out"] =
      s.heightfield ? "the dielectric tables (issue 32): one more reference (energy_audit.h)"
                    : "the random heightfields (opt-in: /references with \"heightfield\", `vgroove energy --audit "
                      "--reference heightfield`) and the dielectric tables (issue 32)";
  j["model_s"] = model_s;

  // The table.
  std::ostringstream os;
  const int reg_rough = 1, reg_grazing = 2;
  for (int ref = 0; ref < kRefs; ++ref) {
    if (!audited(s, ref)) continue;
    os << "  against " << kAuditReferences[ref]
       << (ref == 0   ? " (the V-groove model; formulas fed with the V-cavity single scattering)\n"
           : ref == 1 ? " (the Smith random walk; formulas fed with Smith's height-correlated single scattering,\n"
                        "  @moonray_table with the separable one of MoonRay's lobes)\n"
                      : " (random heightfields traced exactly; formulas fed with Smith's height-correlated single "
                        "scattering,\n  @moonray_table with the separable one of MoonRay's lobes)\n");
    os << support::format("    %-30s %19s %9s %9s %9s %9s %9s %9s\n", "formula (feed)", "grey worst/mean", "rough",
                          "grazing", "conduct.", "engine", "mix-bef.", "mix-aft.");
    for (int v = 0; v < V; ++v) {
      const Stat& g = stat(v, ref, 0, 0);
      if (g.n == 0) continue;
      os << support::format("    %-30s %+9.2e/%8.2e %9.2e %9.2e %9.2e %9.2e %9.2e %9.2e\n", variants[v].id.c_str(),
                            g.worst_signed, g.mean_abs(), stat(v, ref, 0, reg_rough).mean_abs(),
                            stat(v, ref, 0, reg_grazing).mean_abs(), stat(v, ref, 1, 0).mean_abs(),
                            stat(v, ref, 3, 0).mean_abs(), stat(v, ref, 4, 0).mean_abs(),
                            stat(v, ref, 5, 0).mean_abs());
    }
  }
  os << "  (mean |error| unless marked; rough: alpha >= " << support::number_text(s.rough_alpha)
     << ", grazing: mu <= " << support::number_text(s.grazing_mu)
     << "; engine: a metal given as Schlick F0 against its exact conductor)\n";
  for (const auto& [metal, by] : colour.items())
    for (const auto& [given, refs_j] : by.items())
      for (const auto& [ref, vars] : refs_j.items()) {
        os << "  " << metal << " colour shift (" << given << ", against " << ref << "), CIE Delta E 2000 mean/worst:";
        for (const auto& [vid, x] : vars.items()) {
          const nlohmann::json& a = x["all"]["delta_e_2000"];
          if (a.is_null()) continue;
          os << support::format(" %s %.2f/%.2f;", vid.c_str(), a["mean_abs"].get<double>(),
                                std::abs(a["worst"].get<double>()));
        }
        os << "\n";
      }
  os << support::format(
      "  checks: walk white furnace %s (lost %lld, largest |E - 1| %.1e); walk E_1 vs exact E_ss %s (largest %.2f "
      "se at %s); V-groove white furnace %s (%.1e at %s); V-groove E_1 vs V-cavity E_ss %s (%.1e)\n",
      walk_ok ? "ok" : "FAIL", static_cast<long long>(lost), walk_white, z_ok ? "ok" : "FAIL", walk_z,
      walk_z_at.c_str(), vg_ok ? "ok" : "FAIL", vg_white, vg_white_at.c_str(), vg1_ok ? "ok" : "FAIL", vg_single);
  if (s.heightfield)
    os << support::format(
        "  heightfield: white furnace %s (lost %lld, over the bounce limit %lld, largest |E - 1| %.1e); E_1 - Smith's "
        "E_ss (a result): largest %.2f se at %s (%+.4f)\n",
        hf_ok ? "ok" : "FAIL", static_cast<long long>(hf_lost), static_cast<long long>(hf_limit), hf_white, hf_z,
        hf_z_at.c_str(), hf_d1);
  for (const std::string& st : statements)
    if (st.find(", all:") != std::string::npos || st.find(", rough:") != std::string::npos ||
        st.find(", grazing:") != std::string::npos)
      os << "  " << st << "\n";
  run.table = os.str();
  return run;
}

nlohmann::json energy_audit_report_json(const EnergyAuditSuite& s, const EnergyAuditRun& run) {
  nlohmann::json j = report_header({s.name, s.file, "energy_audit", s.description, s.seed}, run.threads, run.wall_s);
  j["spec"] = energy_audit_json(s);
  j["grid"] = {{"ndf", energy_audit_json(s)["ndf"]},
               {"alpha", exact_json(s.alphas)},
               {"mu", exact_json(s.mus)},
               {"layout",
                "arrays [ndf][alpha][mu][channel], E_by_k [ndf][alpha][mu][k][channel] (k = 0..max_k, the "
                "last row k > max_k)"}};
  for (const auto& [k, v] : run.body.items()) j[k] = v;
  j["pass"] = run.pass;
  return j;
}

void print_energy_audit(std::ostream& os, const EnergyAuditSuite& s, const EnergyAuditRun& run) {
  print_table_title(
      os, s.name, "energy_audit",
      support::format("%zu cells (%zu NDFs x %zu alpha x %zu mu), %lld walk paths per cell, seed %llu", s.cells(),
                      s.ndfs.size(), s.alphas.size(), s.mus.size(), s.walk_paths,
                      static_cast<unsigned long long>(s.seed)) +
          (s.heightfield ? support::format("; heightfield: %d fields of %d^2 cells (l = %g), %lld rays "
                                           "per field and cell",
                                           s.hf_fields, s.hf_field_size, s.hf_correlation_length, s.hf_rays_per_field)
                         : std::string()),
      run.threads);
  os << run.table;
  // The verdict is the references' checks; the formulas' errors are results.
  std::size_t passed = 0, total = 0;
  if (run.body.contains("checks"))
    for (const auto& [name, c] : run.body["checks"].items()) ++total, passed += c.value("pass", false) ? 1 : 0;
  print_table_close(os, passed, total, run.wall_s, "reference checks pass (the formulas' errors are results)");
}

}  // namespace vgroove::validation
