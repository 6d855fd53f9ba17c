// vgroove validation: the materials of the energy audit (validation/energy_audit.h) as reflectance
// channels: grey Schlick reflectances, the four metals of data/reference/metals.json as exact
// conductors per wavelength, and the same metals as engines enter them, Schlick's F with the
// metal's normal reflectance per wavelength as F0.
//
// The metals' optical constants are those of data/reference/metals.json (Johnson and Christy 1972
// for Au, Ag, Cu; Rakic 1995 for Al; three tabulated wavelengths near 450, 550 and 650 nm each,
// copied as printed there): tests/validation/energy_materials_test.cpp holds this copy to the file.
// The three wavelengths are the channels of a colour: band 0 (~450 nm) blue, 1 (~550) green,
// 2 (~650) red, read as linear sRGB by the audit's colour shift (energy_audit.h states it).
#pragma once

#include "vgroove/analytic/albedo_vgroove.h"
#include "vgroove/analytic/reflectance_table.h"

#include <string>
#include <vector>

namespace vgroove::validation {

struct ReferenceMetal {
  const char* name;
  const char* symbol;
  double lambda_nm[3];
  double eta[3];
  double kappa[3];
};
// Au, Ag, Cu, Al in that order.
const std::vector<ReferenceMetal>& reference_metals();
// The metal of a symbol ("Au", ...), or null.
const ReferenceMetal* reference_metal(const std::string& symbol);

enum class ChannelKind : unsigned char { schlick, conductor };

struct Channel {
  std::string name;   // "grey 0.04", "Au 450.9 nm", "Au Schlick 450.9 nm"
  std::string group;  // "grey", "conductor", "metal_schlick"
  ChannelKind kind = ChannelKind::schlick;
  double F0 = 0.0;  // the normal reflectance (a conductor's from eta, kappa)
  double eta = 0.0, kappa = 0.0;
  std::string metal;                 // the symbol, for the metals' channels
  int band = -1;                     // 0, 1, 2 for the metals' wavelengths
  double F(double cos_theta) const;  // exact
};

// The channels and what evaluates them fast: conductors through ReflectanceTable (within 4.3e-13
// of the exact curve, analytic/reflectance_table.h), Schlick's F exactly.
class ChannelSet {
 public:
  ChannelSet() = default;
  // grey F0 values, then per metal its three conductor channels, then its three Schlick ones.
  ChannelSet(const std::vector<double>& grey_F0, const std::vector<std::string>& metals);
  const std::vector<Channel>& channels() const { return channels_; }
  int size() const { return static_cast<int>(channels_.size()); }
  // All channels at one cosine (analytic::ChannelReflectance); valid while this set lives.
  analytic::ChannelReflectance reflectance() const;
  void evaluate(double cos_theta, double* out) const;
  // F_avg = 2 int F mu dmu (Kulla and Conty 2017): F0 + (1 - F0)/21 for Schlick, by quadrature
  // (error below 1e-13) for a conductor.
  double F_avg(int c) const { return F_avg_[static_cast<std::size_t>(c)]; }
  // The channel of a group, metal and band; -1 when absent.
  int find(const std::string& group, const std::string& metal, int band) const;
  int find_grey(double F0) const;

 private:
  std::vector<Channel> channels_;
  std::vector<analytic::ReflectanceTable> tables_;  // per channel; empty for Schlick
  std::vector<double> F_avg_;
};

}  // namespace vgroove::validation
