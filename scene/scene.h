// vgroove scene: a scene spec (data/scenes/*.json), read strictly: what to trace, from where,
// with which effects, and what to record. `vgroove simulate SCENE.json` runs it (simulate.h).
//
// Schema (every key is listed; anything else is an error naming its JSON path):
//   {
//     "scene": "gold_groove",                       required, non-empty string
//     "note": "...",                                optional string (where the constants come from)
//     "geometry":                                   required, one of
//       {"kind": "groove", "theta_v_deg": 90}                       symmetric, theta_v in [0.001, 180]
//       {"kind": "groove", "theta_l_deg": -30, "theta_r_deg": 45}   nonsymmetric (Lee et al. 2018, Fig. 5):
//                                                   theta_l in [-90, 0], theta_r in [0, 90], aperture
//                                                   180 + theta_l - theta_r >= 0.001
//       {"kind": "microsurface", "ndf": "ggx" | "beckmann" | "phong", "alpha": 0.5,
//        "grooves": 10000, "seed": 1}               sim/microsurface.h; alpha in [0.01, 2] (the range the
//                                                   slope sampler is tested on), grooves in [1, 10000000],
//                                                   seed in [0, 2^63 - 1] (default 0)
//     "light": {                                    required
//       "theta_i_deg": [0, 30, 60],                 non-empty list, each in [-89.999, 89.999]
//       "rays": 100000,                             per theta_i, [1, 1000000000]: across the groove's
//                                                   opening, or across the whole microsurface
//       "sampling": "stratified" | "random",        optional, default "stratified"
//       "seed": 1},                                 optional, [0, 2^63 - 1], default 1
//     "effects": {                                  required
//       "fresnel":                                  required, one of
//         {"kind": "none"}                          perfect mirrors: nothing is computed per bounce
//         {"kind": "conductor", "channels": [{"name": "r", "eta": 0.2, "kappa": 3.0}, ...]}
//         {"kind": "conductor", "wavelengths": [{"lambda_nm": 550, "eta": 0.4, "kappa": 2.4}, ...]}
//                                                   exact unpolarized conductor Fresnel (optics/fresnel.h)
//                                                   of eta + i kappa, eta in (0, 1000], kappa in [0, 1000];
//                                                   lambda_nm in (0, 100000] names its channel "<lambda>nm"
//         {"kind": "schlick", "channels": [{"name": "r", "F0": 0.9}, ...]}   F0 in [0, 1]
//                                                   1 to 64 channels, names unique and non-empty
//       "record": {                                 optional; counts per bounce count k are always kept
//                                                   (k = 0..4096, larger k in one row ">4096")
//         "theta_o_histograms": {"bins": 90, "max_k": 16},   optional: exit-angle histograms over
//                                                   (-90, 90) deg, bins in [1, 100000], one total and one
//                                                   per k = 0..max_k ([0, 1000], default 16; larger k share
//                                                   a last row); bins x (max_k + 2) <= 1000000
//         "energy_per_k": true},                    optional, default false: the energy per k per channel
//                                                   (needs a Fresnel effect: without one it is the count)
//       "max_bounces": 100000}                      optional, [1, 100000000]: rays still inside are counted
//   }                                               in their own bucket, never dropped
//
// Energy: Lee et al. 2018, Eq. (11): a path keeps the product of F at its bounces' local angles.
// Degrees at this edge only: the spec's *_deg values become radians in Scene.
#pragma once

#include "vgroove/sim/beam.h"
#include "vgroove/sim/slope_sampling.h"
#include "vgroove/validation/groove_suite.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vgroove::scene {

enum class GeometryKind : unsigned char { groove, microsurface };
enum class FresnelKind : unsigned char { none, conductor, schlick };
const char* fresnel_kind_name(FresnelKind k);

struct SceneGeometry {
  GeometryKind kind = GeometryKind::groove;
  validation::GrooveParams groove;       // kind == groove (radians)
  sim::NdfKind ndf = sim::NdfKind::ggx;  // kind == microsurface
  double alpha = 0.5;
  int grooves = 10000;
  std::uint64_t surface_seed = 0;
};

struct SceneLight {
  std::vector<double> theta_i;  // radians
  std::int64_t rays = 0;        // per theta_i
  sim::Sampling sampling = sim::Sampling::stratified;
  std::uint64_t seed = 1;
};

// One channel of the Fresnel effect: a conductor's eta + i kappa (at lambda_nm, when given as a
// wavelength list), or Schlick's F0.
struct FresnelChannel {
  std::string name;
  double eta = 1.0, kappa = 0.0;  // conductor
  double lambda_nm = 0.0;         // conductor given by wavelength; 0 otherwise
  double F0 = 0.0;                // schlick
};

struct SceneRecord {
  int theta_o_bins = 0;  // 0: no histograms
  int histogram_max_k = 16;
  bool energy_per_k = false;
};

inline constexpr int kMaxChannels = 64;
using validation::kMaxHistogramCells;

struct Scene {
  std::string file;
  std::string name;
  std::string note;
  SceneGeometry geometry;
  SceneLight light;
  FresnelKind fresnel = FresnelKind::none;
  std::vector<FresnelChannel> channels;  // empty for fresnel none
  SceneRecord record;
  int max_bounces = 100000;
};

Scene load_scene(const std::string& file);
// The same from parsed JSON; `file` names it in messages.
Scene parse_scene(const nlohmann::json& j, const std::string& file);

}  // namespace vgroove::scene
