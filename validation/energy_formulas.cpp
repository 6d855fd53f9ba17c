#include "vgroove/validation/energy_formulas.h"

#include "vgroove/analytic/albedo_single.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vgroove::validation {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

const char* feed_name(Feed f) {
  switch (f) {
    case Feed::exact:
      return "exact";
    case Feed::cycles_table:
      return "cycles_table";
    case Feed::filament_lut:
      return "filament_lut";
    case Feed::karis_fit:
      return "karis_fit";
  }
  return "?";
}

const std::vector<FormulaVariant>& formula_variants() {
  static const std::vector<FormulaVariant> v = [] {
    std::vector<FormulaVariant> out;
    auto add = [&](const std::string& formula, Feed feed, const std::string& source) {
      out.push_back({feed == Feed::exact ? formula : formula + "@" + feed_name(feed), formula, feed, source});
    };
    add("single", Feed::exact, "single scattering alone: Smith height-correlated or V-cavity f_ss with F");
    const std::string kc = "Kulla and Conty 2017, SIGGRAPH course slides 'Energy compensation' (no equation numbers)";
    add("kulla_conty", Feed::exact, kc);
    add("turquin", Feed::exact, "Turquin 2019, ILM technical report, the compensation factor 1 + F0 (1 - E) / E");
    const std::string cy =
        "Blender Cycles intern/cycles/kernel/closure/bsdf_microfacet.h, microfacet_ggx_preserve_energy";
    add("cycles", Feed::exact, cy);
    add("cycles", Feed::cycles_table, cy);
    add("filament", Feed::filament_lut,
        "Filament docs Sec. 4.7.2 'Energy compensation' (energyCompensation = 1 + f0 (1/dfg.y - 1)); LUT from "
        "cmgen --ibl-dfg (libs/ibl/src/CubemapIBL.cpp)");
    add("bevy_direct", Feed::karis_fit,
        "Bevy crates/bevy_pbr/src/render/pbr_lighting.wgsl specular_multiscatter with F_AB = EnvBRDFApprox");
    const std::string fa = "Fdez-Aguera 2019, JCGT 8(1), as three.js computeMultiscattering";
    add("fdez_aguera", Feed::exact, fa);
    add("fdez_aguera", Feed::karis_fit, fa + " with DFGApprox");
    const std::string fr = "Fdez-Aguera 2019 with the roughness-dependent kS, as Bevy environment_map.wgsl";
    add("fdez_aguera_roughness", Feed::exact, fr);
    add("fdez_aguera_roughness", Feed::karis_fit, fr + " with F_AB = EnvBRDFApprox");
    return out;
  }();
  return v;
}

double compensated_albedo(const FormulaVariant& v, const SingleScattering& s, const EngineValues& e,
                          const ChannelValues& c, double alpha, double mu) {
  const std::string& f = v.formula;
  if (f == "single") return c.E_F;
  if (f == "kulla_conty") return c.E_F + analytic::kulla_conty_fresnel_factor(c.F_avg, s.E_avg) * (1.0 - s.E);
  if (f == "turquin") return c.E_F * analytic::turquin_factor(c.F0, s.E);
  if (f == "filament") return c.E_F * analytic::filament_energy_compensation(c.F0, e.filament_dfg_y);
  if (f == "bevy_direct") return c.E_F * analytic::filament_energy_compensation(c.F0, e.karis.scale + e.karis.bias);
  if (f == "cycles") {
    const double E = v.feed == Feed::cycles_table ? e.cycles_E : s.E;
    const double E_avg = v.feed == Feed::cycles_table ? e.cycles_E_avg : s.E_avg;
    return c.E_F * analytic::cycles_energy_factor(E, E_avg, analytic::fresnel_average_schlick(c.F0));
  }
  const double scale = v.feed == Feed::karis_fit ? e.karis.scale : s.scale;
  const double bias = v.feed == Feed::karis_fit ? e.karis.bias : s.bias;
  if (f == "fdez_aguera") return analytic::fdez_aguera(c.F0, scale, bias).total();
  if (f == "fdez_aguera_roughness")
    return analytic::fdez_aguera_roughness_fresnel(c.F0, scale, bias, std::min(1.0, std::sqrt(alpha)), mu).total();
  return kNaN;
}

extern const char* const kCyclesGgxAlbedoJson;  // generated: validation/cycles_tables_text.cpp.in

namespace {
CyclesTables cycles_tables_from(const nlohmann::json& j, const std::string& file) {
  CyclesTables t;
  try {
    for (const auto& row : j.at("ggx_E")) {
      if (row.size() != 32) throw support::UserError(file + ": /ggx_E rows must hold 32 values");
      for (const auto& v : row) t.E.push_back(v.get<double>());
    }
    for (const auto& v : j.at("ggx_Eavg")) t.E_avg.push_back(v.get<double>());
  } catch (const nlohmann::json::exception& e) {
    throw support::UserError(file + ": not Cycles' albedo tables (" + e.what() + ")");
  }
  if (t.E.size() != 32 * 32 || t.E_avg.size() != 32)
    throw support::UserError(file + ": /ggx_E must be 32 x 32 and /ggx_Eavg 32 values (Cycles' table_ggx_E)");
  return t;
}
}  // namespace

CyclesTables read_cycles_tables(const std::string& file) {
  return cycles_tables_from(support::read_json_file(file), file);
}

const CyclesTables& published_cycles_tables() {
  static const CyclesTables t =
      cycles_tables_from(nlohmann::json::parse(kCyclesGgxAlbedoJson), "data/reference/cycles_ggx_albedo.json");
  return t;
}

namespace {
// Cycles' lookup_table_read: x in [0, 1] over `size` samples at the texel ends, linear.
double lookup_1d(const double* data, double x, int size) {
  x = std::clamp(x, 0.0, 1.0) * (size - 1);
  const int index = std::min(static_cast<int>(x), size - 1), next = std::min(index + 1, size - 1);
  const double t = x - index;
  return t == 0.0 ? data[index] : (1.0 - t) * data[index] + t * data[next];
}
}  // namespace

double cycles_E(const CyclesTables& t, double alpha, double mu) {
  const double rough = std::sqrt(alpha);
  const double y = std::clamp(mu, 0.0, 1.0) * 31.0;
  const int index = std::min(static_cast<int>(y), 31), next = std::min(index + 1, 31);
  const double f = y - index;
  const double d0 = lookup_1d(&t.E[static_cast<std::size_t>(index) * 32], rough, 32);
  if (f == 0.0) return d0;
  return (1.0 - f) * d0 + f * lookup_1d(&t.E[static_cast<std::size_t>(next) * 32], rough, 32);
}

double cycles_E_avg(const CyclesTables& t, double alpha) { return lookup_1d(t.E_avg.data(), std::sqrt(alpha), 32); }

double round_to_half(double v) {
  if (!(std::abs(v) > 0.0) || !std::isfinite(v)) return v;
  int e = 0;
  std::frexp(std::abs(v), &e);  // |v| = m 2^e, m in [0.5, 1)
  // binary16: 11 significant bits for normal values (|v| >= 2^-14), a fixed step 2^-24 below.
  const double step = std::ldexp(1.0, std::max(e - 11, -24));
  return std::nearbyint(v / step) * step;
}

double filament_dfg_y(double alpha, double mu, int n) {
  const analytic::MicrofacetModel ggx{NdfKind::ggx, analytic::MaskingKind::smith_height_correlated};
  analytic::AlbedoOptions opt;
  opt.tol = 1e-10;
  // The texel at column i, GL row j (cmgen, in float).
  auto texel = [&](int i, int j) {
    const float h = static_cast<float>(n);
    const float coord = std::min(1.0f, (static_cast<float>(j) + 1.5f) / h);
    const float NoV = std::min(1.0f, (static_cast<float>(i) + 0.5f) / h);
    const double linear_roughness = static_cast<double>(coord * coord);
    return round_to_half(analytic::albedo_single(ggx, linear_roughness, static_cast<double>(NoV), opt).value);
  };
  // Bilinear at the texel centres, clamped to the edge texels.
  const double x = std::clamp(mu * n - 0.5, 0.0, n - 1.0), y = std::clamp(std::sqrt(alpha) * n - 0.5, 0.0, n - 1.0);
  const int i0 = std::min(static_cast<int>(x), n - 2), j0 = std::min(static_cast<int>(y), n - 2);
  const double tx = x - i0, ty = y - j0;
  return (1.0 - ty) * ((1.0 - tx) * texel(i0, j0) + tx * texel(i0 + 1, j0)) +
         ty * ((1.0 - tx) * texel(i0, j0 + 1) + tx * texel(i0 + 1, j0 + 1));
}

}  // namespace vgroove::validation
