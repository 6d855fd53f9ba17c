#include "vgroove/validation/energy_materials.h"

#include "vgroove/analytic/albedo_single.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/support/user_error.h"

#include <cmath>

namespace vgroove::validation {

const std::vector<ReferenceMetal>& reference_metals() {
  // data/reference/metals.json, rows as printed (lambda_nm, eta = n, kappa = k).
  static const std::vector<ReferenceMetal> m = {
      {"gold", "Au", {450.9, 548.6, 659.5}, {1.38, 0.43, 0.14}, {1.914, 2.455, 3.697}},
      {"silver", "Ag", {450.9, 548.6, 659.5}, {0.04, 0.06, 0.05}, {2.657, 3.586, 4.483}},
      {"copper", "Cu", {450.9, 548.6, 659.5}, {1.24, 1.02, 0.22}, {2.397, 2.577, 3.747}},
      {"aluminium", "Al", {442.8, 563.57, 652.25}, {0.6079, 1.0728, 1.5724}, {5.3676, 6.7839, 7.7354}},
  };
  return m;
}

const ReferenceMetal* reference_metal(const std::string& symbol) {
  for (const ReferenceMetal& m : reference_metals())
    if (symbol == m.symbol) return &m;
  return nullptr;
}

double Channel::F(double cos_theta) const {
  return kind == ChannelKind::schlick ? optics::fresnel_schlick(cos_theta, F0)
                                      : optics::fresnel_conductor(cos_theta, eta, kappa);
}

ChannelSet::ChannelSet(const std::vector<double>& grey_F0, const std::vector<std::string>& metals) {
  for (double F0 : grey_F0) {
    Channel c;
    c.name = "grey " + support::number_text(F0);
    c.group = "grey";
    c.F0 = F0;
    channels_.push_back(c);
  }
  for (const std::string& symbol : metals) {
    const ReferenceMetal* m = reference_metal(symbol);
    if (!m) continue;  // the spec reader names unknown metals
    for (int b = 0; b < 3; ++b) {
      Channel c;
      c.name = symbol + " " + support::number_text(m->lambda_nm[b]) + " nm";
      c.group = "conductor";
      c.kind = ChannelKind::conductor;
      c.eta = m->eta[b], c.kappa = m->kappa[b];
      c.F0 = optics::fresnel_normal_incidence(c.eta, c.kappa);
      c.metal = symbol, c.band = b;
      channels_.push_back(c);
    }
    for (int b = 0; b < 3; ++b) {
      Channel c;
      c.name = symbol + " Schlick " + support::number_text(m->lambda_nm[b]) + " nm";
      c.group = "metal_schlick";
      c.F0 = optics::fresnel_normal_incidence(m->eta[b], m->kappa[b]);
      c.metal = symbol, c.band = b;
      channels_.push_back(c);
    }
  }
  for (const Channel& c : channels_) {
    if (c.kind == ChannelKind::conductor) {
      tables_.emplace_back([c](double x) { return c.F(x); });
      analytic::AlbedoOptions o;
      o.tol = 1e-14;
      F_avg_.push_back(analytic::cosine_weighted_average([&](double mu) { return c.F(mu); }, o).value);
    } else {
      tables_.emplace_back();
      F_avg_.push_back(c.F0 + (1.0 - c.F0) / 21.0);
    }
  }
}

void ChannelSet::evaluate(double cos_theta, double* out) const {
  const std::size_t n = channels_.size();
  // Schlick's (1 - cos)^5 once for every Schlick channel.
  const double x = 1.0 - std::min(1.0, std::max(0.0, cos_theta)), x2 = x * x, w = x2 * x2 * x;
  for (std::size_t c = 0; c < n; ++c) {
    const Channel& ch = channels_[c];
    out[c] = ch.kind == ChannelKind::schlick ? ch.F0 + (1.0 - ch.F0) * w : tables_[c](cos_theta);
  }
}

analytic::ChannelReflectance ChannelSet::reflectance() const {
  return [this](double cos_theta, double* out) { evaluate(cos_theta, out); };
}

int ChannelSet::find(const std::string& group, const std::string& metal, int band) const {
  for (std::size_t c = 0; c < channels_.size(); ++c)
    if (channels_[c].group == group && channels_[c].metal == metal && channels_[c].band == band)
      return static_cast<int>(c);
  return -1;
}

int ChannelSet::find_grey(double F0) const {
  for (std::size_t c = 0; c < channels_.size(); ++c)
    if (channels_[c].group == "grey" && channels_[c].F0 == F0) return static_cast<int>(c);
  return -1;
}

}  // namespace vgroove::validation
