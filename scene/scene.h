// vgroove scene: a scene spec (data/scenes/*.json), read strictly: what to trace (one groove,
// symmetric or nonsymmetric, or a microsurface), from where (theta_i list, rays, stratified or
// random, seed), with which effects (no Fresnel, exact conductor per channel or wavelength, or
// Schlick), and what to record (counts per k always; optional theta_o histograms and energy per
// k). `vgroove simulate SCENE.json` runs it (simulate.h). Every key and its range is listed in
// docs/derivations/scene.md and docs/schemas/; any other key is an error naming its JSON path.
// Energy: Lee et al. 2018, Eq. (11): a path keeps the product of F at its bounces' local angles.
// Degrees at this edge only: the spec's *_deg values become radians in Scene.
// Tests: tests/scene/scene_test.cpp (SceneSpec.UnknownKey, SceneSpec.OutOfRange,
// SceneSpec.NotOneOfTheChoices, SceneSpec.MissingRequiredKey, SceneSpec.InconsistentCombinations,
// SceneSpec.CheckedInScenesParse, SceneSpec.HistogramSizeIsBounded).
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
