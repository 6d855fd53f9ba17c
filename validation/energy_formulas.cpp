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
    case Feed::moonray_table:
      return "moonray_table";
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
    add("kulla_conty", Feed::moonray_table,
        kc + "; as DreamWorks MoonRay ships it (CookTorranceEnergyCompensation.cc) with its ReflectionAlbedo.h "
             "tables, the lobe added only where sqrt(alpha) > 0.5");
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
  if (f == "kulla_conty" && v.feed == Feed::moonray_table) {
    // The lobe (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg)) F_ms over the light's hemisphere.
    const double missing = e.moonray_one_minus_E_avg;
    if (!e.moonray_compensates || missing == 0.0) return c.E_F;  // MoonRay: a zero divisor adds nothing
    return c.E_F + analytic::kulla_conty_fresnel_factor(c.F_avg, 1.0 - missing) * (1.0 - e.moonray_E) *
                       e.moonray_missing_average / missing;
  }
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

extern const char* const kCyclesGgxAlbedoJson;          // generated: validation/reference_text.cpp.in
extern const char* const kMoonrayReflectionAlbedoJson;  // the same

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

namespace {
MoonrayTables moonray_tables_from(const nlohmann::json& j, const std::string& file) {
  constexpr std::size_t n = kMoonrayTableSize;
  MoonrayTables t;
  auto rows = [&](const char* key, std::vector<double>& out) {
    for (const auto& row : j.at(key)) {
      if (row.size() != n) throw support::UserError(file + ": /" + key + " rows must hold 33 values");
      for (const auto& v : row) out.push_back(v.get<double>());
    }
    if (out.size() != n * n) throw support::UserError(file + ": /" + key + " must be 33 x 33 (MoonRay's E table)");
  };
  auto list = [&](const char* key, std::vector<double>& out) {
    for (const auto& v : j.at(key)) out.push_back(v.get<double>());
    if (out.size() != n) throw support::UserError(file + ": /" + key + " must hold 33 values (MoonRay's 1 - E_avg)");
  };
  try {
    rows("ggx_E", t.ggx_E), rows("beckmann_E", t.beckmann_E);
    list("ggx_one_minus_E_avg", t.ggx_one_minus_E_avg), list("beckmann_one_minus_E_avg", t.beckmann_one_minus_E_avg);
  } catch (const nlohmann::json::exception& e) {
    throw support::UserError(file + ": not MoonRay's albedo tables (" + e.what() + ")");
  }
  return t;
}

// ReflectionAlbedo::rIndex in float: the row below r * 32 and the weight of the next.
std::size_t moonray_row(double alpha, float& w) {
  const float i = static_cast<float>(std::sqrt(alpha)) * static_cast<float>(kMoonrayTableSize - 1);
  const float below = std::floor(i);
  w = i - below;
  return static_cast<std::size_t>(below);
}

// scene_rdl2::math::lerp.
float lerp(float a, float b, float w) { return (1.0f - w) * a + w * b; }
}  // namespace

MoonrayTables read_moonray_tables(const std::string& file) {
  return moonray_tables_from(support::read_json_file(file), file);
}

const MoonrayTables& published_moonray_tables() {
  static const MoonrayTables t = moonray_tables_from(nlohmann::json::parse(kMoonrayReflectionAlbedoJson),
                                                     "data/reference/moonray_reflection_albedo.json");
  return t;
}

double moonray_E(const MoonrayTables& t, NdfKind ndf, double alpha, double mu) {
  constexpr std::size_t n = kMoonrayTableSize;
  float w = 0.0f;
  const std::size_t low = moonray_row(alpha, w), high = std::min(low + 1, n - 1);
  // ReflectionAlbedo::index: ceil(row * 33 + cos * 32) in float, the same column for both rows
  // but where the float sum rounds differently (it does not for rows <= 32).
  const float c = static_cast<float>(mu) * static_cast<float>(n - 1);
  const auto at = [&](std::size_t row) {
    const auto flat = static_cast<std::size_t>(std::ceil(static_cast<float>(row * n) + c));
    return static_cast<float>(t.E(ndf)[std::min(flat, row * n + n - 1)]);
  };
  return lerp(at(low), at(high), w);
}

double moonray_one_minus_E_avg(const MoonrayTables& t, NdfKind ndf, double alpha) {
  float w = 0.0f;
  const std::size_t low = moonray_row(alpha, w), high = std::min<std::size_t>(low + 1, kMoonrayTableSize - 1);
  const std::vector<double>& v = t.one_minus_E_avg(ndf);
  return lerp(static_cast<float>(v[low]), static_cast<float>(v[high]), w);
}

double moonray_missing_average(const MoonrayTables& t, NdfKind ndf, double alpha) {
  constexpr int n = kMoonrayTableSize - 1;
  double sum = 0.0;
  for (int j = 1; j <= n; ++j) {
    // E is column j's on ((j - 1) / 32, j / 32]; 2 int x dx over it is (j^2 - (j - 1)^2) / 32^2.
    const double E = moonray_E(t, ndf, alpha, (j - 0.5) / n);
    sum += (1.0 - E) * static_cast<double>(2 * j - 1) / static_cast<double>(n * n);
  }
  return sum;
}

bool moonray_compensates(double alpha) { return std::max(0.0f, static_cast<float>(std::sqrt(alpha)) - 0.5f) > 0.0f; }

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
