#include "vgroove/scene/scene.h"
#include "vgroove/common/angles.h"

#include "vgroove/support/json_reader.h"

#include <cmath>
#include <limits>
#include <set>

namespace vgroove::scene {

using namespace validation;

namespace {

std::string at(const support::JsonObject& o, const std::string& key, std::size_t n) {
  return o.file() + ": " + o.path(key) + "/" + std::to_string(n);
}

// A non-empty JSON list under `key`; `what` describes its items for the message.
const nlohmann::json& read_list(support::JsonObject& o, const std::string& key, const std::string& what,
                                std::size_t max_items) {
  const nlohmann::json& v = o.raw(key);
  if (!v.is_array()) o.fail(key, "= " + support::value_text(v) + " must be a list of " + what);
  if (v.empty()) o.fail(key, "is an empty list (it needs at least one of " + what + ")");
  if (v.size() > max_items)
    o.fail(key, "has " + std::to_string(v.size()) + " items, more than the " + std::to_string(max_items) + " allowed");
  return v;
}

SceneGeometry read_geometry(support::JsonObject& g) {
  SceneGeometry s;
  if (g.one_of("kind", {"groove", "microsurface"}) == "groove") {
    s.kind = GeometryKind::groove;
    if (g.has("theta_v_deg")) {
      if (g.has("theta_l_deg") || g.has("theta_r_deg"))
        g.fail("theta_v_deg", "cannot be combined with theta_l_deg/theta_r_deg (the aperture follows from them)");
      s.groove = GrooveParams::make_symmetric(g.number("theta_v_deg", kMinApertureDeg, true, 180.0, true) * kRadPerDeg);
    } else {
      const double l = g.number("theta_l_deg", -90.0, true, 0.0, true);
      const double r = g.number("theta_r_deg", 0.0, true, 90.0, true);
      const double v = 180.0 + l - r;
      if (!(v >= kMinApertureDeg))
        throw support::UserError(g.file() + ": " + g.pointer() + ": theta_l_deg = " + support::number_text(l) +
                                 ", theta_r_deg = " + support::number_text(r) +
                                 " give the aperture 180 + theta_l - theta_r = " + support::number_text(v) +
                                 " deg, out of range [" + support::number_text(kMinApertureDeg) + ", 180]");
      s.groove = GrooveParams::make_nonsymmetric(l * kRadPerDeg, r * kRadPerDeg);
    }
  } else {
    s.kind = GeometryKind::microsurface;
    const std::string ndf = g.one_of("ndf", {"ggx", "beckmann", "phong"});
    s.ndf = *ndf_from_name(ndf);
    s.alpha = g.number("alpha", kMinAlpha, true, kMaxAlpha, true);
    s.grooves = static_cast<int>(g.integer("grooves", 1, kMaxGrooves));
    s.surface_seed = static_cast<std::uint64_t>(g.integer_or("seed", 0, 0, kMaxSeed));
  }
  g.finish();
  return s;
}

SceneLight read_light(support::JsonObject& l) {
  SceneLight s;
  const std::string range = theta_i_range_text();
  const nlohmann::json& list = read_list(l, "theta_i_deg", "incident angles in degrees, each in " + range, 100000);
  for (std::size_t n = 0; n < list.size(); ++n) {
    const nlohmann::json& v = list[n];
    if (!v.is_number())
      throw support::UserError(at(l, "theta_i_deg", n) + " = " + support::value_text(v) + " must be a number");
    const double d = v.get<double>();
    if (!(std::isfinite(d) && d >= -kMaxThetaIDeg && d <= kMaxThetaIDeg))
      throw support::UserError(at(l, "theta_i_deg", n) + " = " + support::value_text(v) + " is out of range " + range);
    s.theta_i.push_back(d * kRadPerDeg);
  }
  s.rays = l.integer("rays", 1, kMaxRays);
  const std::string stratified = "stratified";
  s.sampling = l.one_of("sampling", {"stratified", "random"}, &stratified) == "random" ? sim::Sampling::random
                                                                                       : sim::Sampling::stratified;
  s.seed = static_cast<std::uint64_t>(l.integer_or("seed", 1, 0, kMaxSeed));
  l.finish();
  return s;
}

// The channels of a conductor (by name or by wavelength) or of Schlick's approximation.
std::vector<FresnelChannel> read_channels(support::JsonObject& f, FresnelKind kind) {
  std::string key = "channels";
  if (kind == FresnelKind::conductor) {
    const bool by_name = f.has("channels"), by_wavelength = f.has("wavelengths");
    if (by_name && by_wavelength)
      f.fail("wavelengths", "cannot be combined with channels (give one list: named channels or wavelengths)");
    if (!by_name && !by_wavelength)
      f.fail("channels", "is missing (required: a conductor needs \"channels\" or \"wavelengths\")");
    if (by_wavelength) key = "wavelengths";
  }
  const std::string what = kind == FresnelKind::schlick ? "{\"name\", \"F0\"}"
                           : key == "channels"          ? "{\"name\", \"eta\", \"kappa\"}"
                                                        : "{\"lambda_nm\", \"eta\", \"kappa\"}";
  const nlohmann::json& list = read_list(f, key, what, kMaxChannels);
  std::vector<FresnelChannel> out;
  std::set<std::string> names;
  for (std::size_t n = 0; n < list.size(); ++n) {
    support::JsonObject c(list[n], f.file(), f.path(key) + "/" + std::to_string(n));
    FresnelChannel ch;
    if (key == "wavelengths") {
      ch.lambda_nm = c.number("lambda_nm", 0.0, false, 100000.0, true);
      ch.name = support::number_text(ch.lambda_nm) + "nm";
    } else {
      ch.name = c.string("name");
      if (ch.name.empty()) c.fail("name", "= \"\" must be a non-empty string");
    }
    if (!names.insert(ch.name).second)
      throw support::UserError(c.file() + ": " + c.pointer() + " repeats the channel \"" + ch.name +
                               "\" (names must be unique)");
    if (kind == FresnelKind::schlick) {
      ch.F0 = c.number("F0", 0.0, true, 1.0, true);
    } else {
      ch.eta = c.number("eta", 0.0, false, 1000.0, true);
      ch.kappa = c.number("kappa", 0.0, true, 1000.0, true);
    }
    c.finish();
    out.push_back(ch);
  }
  return out;
}

}  // namespace

const char* fresnel_kind_name(FresnelKind k) {
  switch (k) {
    case FresnelKind::none:
      return "none";
    case FresnelKind::conductor:
      return "conductor";
    case FresnelKind::schlick:
      return "schlick";
  }
  return "?";
}

Scene parse_scene(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  Scene s;
  s.file = file;
  s.name = root.string("scene");
  if (s.name.empty()) root.fail("scene", "= \"\" must be a non-empty string");
  s.note = root.string_or("note", "");
  {
    support::JsonObject g = root.object("geometry");
    s.geometry = read_geometry(g);
  }
  {
    support::JsonObject l = root.object("light");
    s.light = read_light(l);
  }
  {
    support::JsonObject e = root.object("effects");
    {
      support::JsonObject f = e.object("fresnel");
      const std::string kind = f.one_of("kind", {"none", "conductor", "schlick"});
      s.fresnel = kind == "none"        ? FresnelKind::none
                  : kind == "conductor" ? FresnelKind::conductor
                                        : FresnelKind::schlick;
      if (s.fresnel != FresnelKind::none) s.channels = read_channels(f, s.fresnel);
      f.finish();
    }
    if (e.has("record")) {
      support::JsonObject r = e.object("record");
      if (r.has("theta_o_histograms")) {
        support::JsonObject h = r.object("theta_o_histograms");
        s.record.theta_o_bins = static_cast<int>(h.integer("bins", 1, 100000));
        s.record.histogram_max_k = static_cast<int>(h.integer_or("max_k", 16, 0, kMaxHistogramK));
        // Each work item holds its own histograms: bound their size (8 MB of counts).
        const long long cells = static_cast<long long>(s.record.theta_o_bins) * (s.record.histogram_max_k + 2);
        if (cells > kMaxHistogramCells)
          throw support::UserError(h.file() + ": " + h.pointer() + ": bins x (max_k + 2) = " + std::to_string(cells) +
                                   " histogram cells, out of range [1, " + std::to_string(kMaxHistogramCells) + "]");
        h.finish();
      }
      s.record.energy_per_k = r.boolean_or("energy_per_k", false);
      if (s.record.energy_per_k && s.fresnel == FresnelKind::none)
        r.fail("energy_per_k",
               "= true needs a Fresnel effect (with /effects/fresnel/kind = \"none\" every path "
               "keeps all its energy: the energy per k is the count per k)");
      r.finish();
    }
    // By default every ray of a single groove may leave; a microsurface keeps the plain default
    // (its narrowest grooves are drawn at random: the rays still inside are counted apart).
    const int max_bounces =
        s.geometry.kind == GeometryKind::groove ? default_max_bounces(s.geometry.groove.theta_v) : kDefaultMaxBounces;
    s.max_bounces = static_cast<int>(e.integer_or("max_bounces", max_bounces, 1, kMaxBounces));
    e.finish();
  }
  root.finish();
  return s;
}

Scene load_scene(const std::string& file) { return parse_scene(support::read_json_file(file), file); }

}  // namespace vgroove::scene
