#include "vgroove/validation/energy_export.h"

#include "vgroove/analytic/albedo_vgroove.h"
#include "vgroove/analytic/smith_walk_3d.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/format.h"
#include "vgroove/support/npy.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/report.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

namespace vgroove::validation {

namespace {
constexpr std::uint64_t kExportWalkStream = 0x6578706f7274ULL;  // "export"
}

void check_energy_export(const EnergyExportOptions& o) {
  if (o.layout != "cycles" && o.layout != "centres")
    throw support::UserError("--layout = \"" + o.layout + "\" is not one of \"cycles\", \"centres\"");
  if (o.size < 2 || o.size > kMaxExportSize)
    throw support::UserError("--size = " + std::to_string(o.size) + " is out of range [2, " +
                             std::to_string(kMaxExportSize) + "]");
  if (o.ms_reference != "none" && o.ms_reference != "vgroove" && o.ms_reference != "smith_walk")
    throw support::UserError("--ms-reference = \"" + o.ms_reference +
                             "\" is not one of \"none\", \"vgroove\", \"smith_walk\"");
  if (o.model.ndf == NdfKind::phong)
    throw support::UserError("--ndf = phong: the export takes ggx or beckmann (Smith's G2 needs Lambda)");
  if (o.ms_reference != "none" && (o.ms_F0.empty() || o.ms_F0.size() > kMaxExportF0))
    throw support::UserError("--ms-F0 has " + std::to_string(o.ms_F0.size()) + " values, out of range [1, " +
                             std::to_string(kMaxExportF0) + "]");
  for (double F0 : o.ms_F0)
    if (!(F0 >= 0.0 && F0 <= 1.0))
      throw support::UserError("--ms-F0 = " + support::number_text(F0) + " is out of range [0, 1]");
  if (o.walk_paths < 1 || o.walk_paths > kMaxAuditPaths)
    throw support::UserError("--rays = " + std::to_string(o.walk_paths) + " is out of range [1, " +
                             std::to_string(kMaxAuditPaths) + "]");
}

analytic::TableLayout export_layout(const EnergyExportOptions& o) {
  analytic::TableLayout l = analytic::cycles_ggx_E_layout();
  l.n_direction = l.n_roughness = o.size;
  if (o.layout == "centres") {
    l.placement = analytic::TexelPlacement::centers;
    l.s_min = 0.0;
    l.float_coordinates = false;
    l.saturate = false;
  }
  return l;
}

std::optional<EnergyExport> energy_export(const EnergyExportOptions& o, const support::ProgressFn& progress,
                                          const std::atomic<bool>* cancel) {
  check_energy_export(o);
  const auto t0 = std::chrono::steady_clock::now();
  const analytic::TableLayout l = export_layout(o);
  analytic::MicrofacetModel model = o.model;
  if (o.ms_reference == "smith_walk") model.masking = analytic::MaskingKind::smith_height_correlated;
  if (o.ms_reference == "vgroove") model.masking = analytic::MaskingKind::vcavity;
  const int nd = l.n_direction, nr = l.n_roughness, nf = static_cast<int>(o.ms_F0.size());
  const std::size_t texels = static_cast<std::size_t>(nd) * nr;
  const bool ms = o.ms_reference != "none";
  std::vector<double> E(texels), scale(texels), bias(texels), bound(texels), E_avg(nr), avg_bound(nr);
  std::vector<double> E_ms(ms ? texels * nf : 0), E_ms_se(ms ? texels * nf : 0);
  analytic::AlbedoOptions opt;
  opt.tol = o.tol;
  auto schlick_channels = [&](double c, double* out) {
    for (int f = 0; f < nf; ++f) out[f] = optics::fresnel_schlick(c, o.ms_F0[static_cast<std::size_t>(f)]);
  };
  // Items: the texels, then the averages per roughness column.
  const bool complete = support::parallel_for(
      texels + static_cast<std::size_t>(nr), support::resolve_threads(o.threads),
      [&](std::size_t q) {
        if (q >= texels) {
          const int j = static_cast<int>(q - texels);
          const analytic::BoundedValue a = analytic::albedo_average(model, analytic::layout_alpha(l, j), opt);
          E_avg[static_cast<std::size_t>(j)] = a.value, avg_bound[static_cast<std::size_t>(j)] = a.error;
          return;
        }
        const int i = static_cast<int>(q) / nr, j = static_cast<int>(q) % nr;
        const std::size_t k = static_cast<std::size_t>(analytic::layout_index(l, i, j));
        const double mu = analytic::layout_mu(l, i), alpha = analytic::layout_alpha(l, j);
        const analytic::BoundedValue e = analytic::albedo_single(model, alpha, mu, opt);
        const analytic::SplitSum s = analytic::dfg_split_sum(model, alpha, mu, opt);
        E[k] = e.value, scale[k] = s.scale.value, bias[k] = s.bias.value;
        bound[k] = std::max({e.error, s.scale.error, s.bias.error});
        if (!ms) return;
        if (o.ms_reference == "vgroove") {
          const analytic::VgrooveAlbedo v = analytic::vgroove_albedo(model.ndf, alpha, mu, nf, schlick_channels, 1);
          for (int f = 0; f < nf; ++f) E_ms[static_cast<std::size_t>(f) * texels + k] = v.row(2, f);
          return;
        }
        // The Smith walk: the energy leaving after two or more reflections, per F0.
        sim::Rng rng(sim::splitmix64(o.seed ^ kExportWalkStream), k, 0);
        auto uniform = [&rng] { return sim::uniform_open(rng); };
        const analytic::Dir3 in{std::sqrt((1.0 - mu) * (1.0 + mu)), 0.0, mu};
        std::vector<double> prod(static_cast<std::size_t>(nf)), f(static_cast<std::size_t>(nf)),
            sum(static_cast<std::size_t>(nf), 0.0);
        for (long long p = 0; p < o.walk_paths; ++p) {
          std::fill(prod.begin(), prod.end(), 1.0);
          const analytic::Walk3d w = analytic::smith_walk_3d(
              model.ndf, alpha, in, uniform,
              [&](double c) {
                schlick_channels(c, f.data());
                for (int g = 0; g < nf; ++g) prod[static_cast<std::size_t>(g)] *= f[static_cast<std::size_t>(g)];
              },
              100000);
          if (!w.left || w.k < 2) continue;
          for (int g = 0; g < nf; ++g) sum[static_cast<std::size_t>(g)] += prod[static_cast<std::size_t>(g)];
        }
        for (int g = 0; g < nf; ++g) {
          const double m = sum[static_cast<std::size_t>(g)] / static_cast<double>(o.walk_paths);
          E_ms[static_cast<std::size_t>(g) * texels + k] = m;
          E_ms_se[static_cast<std::size_t>(g) * texels + k] =
              std::sqrt(std::max(0.0, m * (1.0 - m)) / static_cast<double>(o.walk_paths));
        }
      },
      progress, cancel, 1);
  if (!complete || support::cancelled(cancel)) return std::nullopt;

  EnergyExport out;
  const std::vector<std::string> axes2 = l.fast == analytic::FastAxis::roughness ? std::vector<std::string>{"mu", "r"}
                                                                                 : std::vector<std::string>{"r", "mu"};
  const std::vector<std::size_t> shape2 = l.fast == analytic::FastAxis::roughness
                                              ? std::vector<std::size_t>{std::size_t(nd), std::size_t(nr)}
                                              : std::vector<std::size_t>{std::size_t(nr), std::size_t(nd)};
  out.arrays.push_back({"E_ss", "single-scattering directional albedo, F = 1", axes2, shape2, E});
  out.arrays.push_back({"E_avg", "its cosine-weighted average 2 int E_ss mu dmu", {"r"}, {std::size_t(nr)}, E_avg});
  out.arrays.push_back(
      {"dfg_scale",
       "split-sum scale: int (1 - Fc) f_ss cos, Fc = (1 - v.h)^5 (albedo with Schlick's F = F0 scale + bias)", axes2,
       shape2, scale});
  out.arrays.push_back({"dfg_bias", "split-sum bias: int Fc f_ss cos", axes2, shape2, bias});
  if (ms) {
    std::vector<std::string> axes3{"F0"};
    axes3.insert(axes3.end(), axes2.begin(), axes2.end());
    std::vector<std::size_t> shape3{std::size_t(nf)};
    shape3.insert(shape3.end(), shape2.begin(), shape2.end());
    std::vector<double> factor(E_ms.size());
    for (int f = 0; f < nf; ++f)
      for (std::size_t t = 0; t < texels; ++t) {
        const double E_F = o.ms_F0[static_cast<std::size_t>(f)] * scale[t] + bias[t];
        factor[static_cast<std::size_t>(f) * texels + t] = (E_F + E_ms[static_cast<std::size_t>(f) * texels + t]) / E_F;
      }
    out.arrays.push_back({"E_ms",
                          "the exact multiple-scattering albedo with Schlick's F per reflection: what leaves after two "
                          "or more reflections",
                          axes3, shape3, E_ms});
    out.arrays.push_back({"compensation",
                          "(E_F + E_ms) / E_F, E_F = F0 dfg_scale + dfg_bias: the exact albedo over the "
                          "single-scattering one with the same F",
                          axes3, shape3, factor});
    if (o.ms_reference == "smith_walk")
      out.arrays.push_back({"E_ms_se", "E_ms's standard error (at most sqrt(E (1 - E) / N), the weights in [0, 1])",
                            axes3, shape3, E_ms_se});
  }
  nlohmann::json mus = nlohmann::json::array(), rs = nlohmann::json::array(), alphas = nlohmann::json::array();
  for (int i = 0; i < nd; ++i) mus.push_back(exact_json(analytic::layout_mu(l, i)));
  for (int j = 0; j < nr; ++j) {
    rs.push_back(exact_json(analytic::layout_coordinate(l, j, nr)));
    alphas.push_back(exact_json(analytic::layout_alpha(l, j)));
  }
  nlohmann::json arrays;
  for (const ExportArray& a : out.arrays)
    arrays[a.name] = {{"shape", a.shape}, {"axes", a.axes}, {"description", a.description}};
  nlohmann::json m = provenance();
  m["command"] = "vgroove energy --export";
  m["layout"] = {
      {"name", o.layout},
      {"n_direction", nd},
      {"n_roughness", nr},
      {"direction", "mu = cos theta_i (the view in the split sum)"},
      {"roughness", "r, alpha = r^2 (GGX/Beckmann width)"},
      {"placement", o.layout == "cycles" ? "texel ends: s = i / (n - 1)" : "texel centres: s = (i + 1/2) / n"},
      {"clamp", o.layout == "cycles" ? "s in [1e-4, 1]" : "none"},
      {"coordinates_in_float", l.float_coordinates},
      {"memory_order", "[direction][roughness], roughness fastest (row = mu index, column = r index)"},
      {"mu", mus},
      {"r", rs},
      {"alpha", alphas}};
  m["model"] = {{"ndf", ndf_name(model.ndf)}, {"masking", analytic::masking_name(model.masking)}};
  m["quadrature"] = {
      {"method", "nested adaptive Gauss-Kronrod with an error bound per value (analytic/albedo_single.h)"},
      {"tol", o.tol},
      {"largest_bound", exact_json(*std::max_element(bound.begin(), bound.end()))},
      {"largest_bound_E_avg", exact_json(*std::max_element(avg_bound.begin(), avg_bound.end()))}};
  if (ms) {
    nlohmann::json r = {{"reference", o.ms_reference},
                        {"F0", exact_json(o.ms_F0)},
                        {"fresnel", "Schlick: F0 + (1 - F0)(1 - cos)^5 at each reflection's local angle"}};
    if (o.ms_reference == "smith_walk")
      r["method"] = "the 3D Smith random walk (Heitz et al. 2016; analytic/smith_walk_3d.h), Monte Carlo",
      r["paths"] = o.walk_paths, r["seed"] = o.seed, r["streams"] = "texel index (memory order), one stream each";
    else
      r["method"] = "the 3D V-groove model (Lee et al. 2018; analytic/albedo_vgroove.h), quadrature to ~1e-8";
    m["multiple_scattering"] = r;
  }
  m["arrays"] = arrays;
  m["encodings"] = {
      {"json", "arrays nested, doubles exact"},
      {"npz", "numpy: one .npy member per array (float64), metadata.json beside them"},
      {"header", "C/C++: static const float arrays, row-major, dimensions as enum constants"},
      {"png",
       "16-bit grey per 2D table (per F0 slice), value = round(v * 65535) / 65535 for v in [0, 1] (the "
       "compensation factor as round(v / 4 * 65535): values up to 4), row y = direction index, column x = "
       "roughness index; this metadata in a tEXt chunk 'vgroove'"},
      {"exr",
       "OpenEXR, 32-bit float channels, one per 2D table (and F0 slice), same rows and columns; E_avg in the "
       "header attribute 'vgroove' with this metadata"}};
  out.metadata = m;
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

std::string export_json_text(const EnergyExport& e) {
  nlohmann::json j = e.metadata;
  nlohmann::json arrays;
  for (const ExportArray& a : e.arrays) {
    // Nested lists of the array's shape.
    std::function<nlohmann::json(std::size_t, std::size_t)> build = [&](std::size_t dim, std::size_t offset) {
      nlohmann::json out = nlohmann::json::array();
      std::size_t stride = 1;
      for (std::size_t d = dim + 1; d < a.shape.size(); ++d) stride *= a.shape[d];
      for (std::size_t i = 0; i < a.shape[dim]; ++i)
        out.push_back(dim + 1 == a.shape.size() ? exact_json(a.values[offset + i])
                                                : build(dim + 1, offset + i * stride));
      return out;
    };
    arrays[a.name] = build(0, 0);
  }
  j["values"] = arrays;
  j["wall_s"] = e.wall_s;
  return j.dump(1) + "\n";
}

namespace {

// CRC-32 (ISO 3309, the zip format's), bitwise by a table.
std::uint32_t crc32(const std::string& bytes) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) c = table[(c ^ b) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

void put16(std::string& s, unsigned v) {
  s.push_back(static_cast<char>(v & 0xff));
  s.push_back(static_cast<char>((v >> 8) & 0xff));
}
void put32(std::string& s, std::uint32_t v) {
  put16(s, v & 0xffff);
  put16(s, v >> 16);
}

}  // namespace

std::string export_npz_bytes(const EnergyExport& e) {
  // A zip archive of stored (uncompressed) members: what numpy.savez writes.
  std::vector<std::pair<std::string, std::string>> members;
  for (const ExportArray& a : e.arrays) members.emplace_back(a.name + ".npy", support::npy_bytes(a.values, a.shape));
  members.emplace_back("metadata.json", e.metadata.dump(1) + "\n");
  std::string out, central;
  for (const auto& [name, data] : members) {
    if (data.size() > 0xffffffffu || out.size() > 0xffffffffu)
      throw support::UserError("--export: a table of " + std::to_string(data.size()) +
                               " bytes is beyond a zip member's 4 GiB (use a smaller --size)");
    const std::uint32_t crc = crc32(data), offset = static_cast<std::uint32_t>(out.size());
    const auto size = static_cast<std::uint32_t>(data.size());
    // Local header: signature, version 2.0, no flags, stored, time 0, date 1980-01-01.
    put32(out, 0x04034b50u), put16(out, 20), put16(out, 0), put16(out, 0), put16(out, 0), put16(out, 0x21);
    put32(out, crc), put32(out, size), put32(out, size), put16(out, static_cast<unsigned>(name.size())), put16(out, 0);
    out += name;
    out += data;
    put32(central, 0x02014b50u), put16(central, 20), put16(central, 20), put16(central, 0), put16(central, 0);
    put16(central, 0), put16(central, 0x21), put32(central, crc), put32(central, size), put32(central, size);
    put16(central, static_cast<unsigned>(name.size())), put16(central, 0), put16(central, 0), put16(central, 0);
    put16(central, 0), put32(central, 0), put32(central, offset);
    central += name;
  }
  const auto cd_offset = static_cast<std::uint32_t>(out.size()), cd_size = static_cast<std::uint32_t>(central.size());
  out += central;
  put32(out, 0x06054b50u), put16(out, 0), put16(out, 0);
  put16(out, static_cast<unsigned>(members.size())), put16(out, static_cast<unsigned>(members.size()));
  put32(out, cd_size), put32(out, cd_offset), put16(out, 0);
  return out;
}

std::string c_identifier(const std::string& base) {
  std::string name = base;
  if (const auto slash = name.find_last_of('/'); slash != std::string::npos) name = name.substr(slash + 1);
  std::string out;
  for (char c : name) out.push_back(std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out.front()))) out = "vgroove_" + out;
  return out;
}

std::string export_header_text(const EnergyExport& e, const std::string& prefix) {
  std::string s = "// Generated by vgroove energy --export: energy tables engines can load.\n//\n";
  // The metadata as a comment, line by line ("*/" cannot end a line comment).
  std::string meta = e.metadata.dump(1);
  std::size_t b = 0;
  while (b < meta.size()) {
    const std::size_t n = meta.find('\n', b);
    s += "// " + meta.substr(b, n == std::string::npos ? std::string::npos : n - b) + "\n";
    if (n == std::string::npos) break;
    b = n + 1;
  }
  s += "#pragma once\n\n";
  for (const ExportArray& a : e.arrays) {
    std::string dims, total;
    for (std::size_t d = 0; d < a.shape.size(); ++d) {
      const std::string dn = prefix + "_" + a.name + "_N" + std::to_string(d);
      s += "enum { " + dn + " = " + std::to_string(a.shape[d]) + " };  // " + a.axes[d] + "\n";
      total += (d ? " * " : "") + dn;
    }
    s += "// " + a.description + "\nstatic const float " + prefix + "_" + a.name + "[" + total + "] = {";
    for (std::size_t i = 0; i < a.values.size(); ++i) {
      if (i % 8 == 0) s += "\n   ";
      std::string v = support::format("%.9g", a.values[i]);
      if (v.find_first_of(".en") == std::string::npos) v += ".0";  // a float literal needs a point
      s += " " + v + "f,";
    }
    s += "\n};\n\n";
  }
  return s;
}

}  // namespace vgroove::validation
