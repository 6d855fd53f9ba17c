// vgroove validation: the white furnace of the BRDF itself (suite kind "furnace"; Lee et al. 2018,
// Fig. 12; Heitz et al. 2016): with F = 1 every ray that enters a groove leaves it, so the albedo of
// the multiple-scattering BRDF must be 1. Per case: albedo_quadrature (Eq. 17 integrated by
// deterministic adaptive quadrature) + flux_beyond_max_k = 1 within the quadrature's tolerance;
// albedo_estimate (Monte Carlo with the sampler's pdf) + flux_beyond_max_k = 1 within sigmas
// standard errors (+1e-12); Cook-Torrance's two routes agree (1 - albedo is what it loses);
// albedo_sim is the tracer's bookkeeping. Tests: tests/validation/furnace_suite_test.cpp
// (FurnaceSuite.Eq17PassesBothRoutes, FurnaceSuite.BrokenJacobianFailsBothRoutes,
// FurnaceSuite.BadSpecsNameTheField, FurnaceSuite.ShippedSuiteParses).
// Derivation: docs/derivations/validation.md.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/facet_strategy.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/item_work.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

struct FurnaceSuite {
  std::string file, name, description;
  std::vector<analytic::NdfKind> ndfs;
  std::vector<double> alphas;
  std::vector<double> theta_i;  // radians
  std::vector<SurfaceDim> dims;
  int max_k = 256;
  long samples = 20000;  // the estimator's
  analytic::FacetStrategy strategy = analytic::FacetStrategy::vndf;
  long rays = 20000;  // the simulated sanity line
  int grooves = 20000;
  std::uint64_t seed = 1;
  double sigmas = 5.0;
  double tolerance_flatland = 1e-9, tolerance_3d = 1e-6;  // the quadratures' absolute tolerances
  std::size_t cases() const { return ndfs.size() * alphas.size() * theta_i.size() * dims.size(); }
  BrdfCase case_at(std::size_t c) const;  // order: dimension, ndf, alpha, theta_i (innermost)
};

struct FurnaceOutcome {
  BrdfCase c;
  double albedo_quadrature = 0.0, quadrature_error = 0.0;
  double flux_beyond_max_k = 0.0;
  double albedo_estimate = 0.0, standard_error = 0.0;
  double cook_torrance_quadrature = 0.0, cook_torrance_estimate = 0.0, cook_torrance_standard_error = 0.0;
  double albedo_sim = 0.0;
  long rays = 0, in_flight = 0;  // the sanity line: rays, and those still inside at the bounce limit
  double quadrature_s = 0.0, estimate_s = 0.0, sim_s = 0.0;
  bool energy_ok = false, estimate_ok = false, cook_torrance_ok = false, sim_ok = false, finite = false;
  bool pass = false;
};

// Its members for a shard part (outcome_fields.h); the case is the suite's.
template <class F>
void fields(FurnaceOutcome& o, F&& f) {
  f("albedo_quadrature", o.albedo_quadrature), f("quadrature_error", o.quadrature_error);
  f("flux_beyond_max_k", o.flux_beyond_max_k);
  f("albedo_estimate", o.albedo_estimate), f("standard_error", o.standard_error);
  f("cook_torrance_quadrature", o.cook_torrance_quadrature), f("cook_torrance_estimate", o.cook_torrance_estimate);
  f("cook_torrance_standard_error", o.cook_torrance_standard_error);
  f("albedo_sim", o.albedo_sim), f("rays", o.rays), f("in_flight", o.in_flight);
  f("quadrature_s", o.quadrature_s), f("estimate_s", o.estimate_s), f("sim_s", o.sim_s);
  f("energy_ok", o.energy_ok), f("estimate_ok", o.estimate_ok), f("cook_torrance_ok", o.cook_torrance_ok);
  f("sim_ok", o.sim_ok), f("finite", o.finite), f("pass", o.pass);
}

struct FurnaceRun {
  std::vector<FurnaceOutcome> cases;
  int threads = 1;
  double wall_s = 0.0;
  bool interrupted = false;
  bool pass = false;
};

// The BRDF under test, pointwise: 3D rho(i, o) and flatland rho2(theta_i, theta_o). Empty: Eq. (17)
// with N = max_k (vgroove_brdf, flatland_brdf_fast). The tests pass deliberately broken variants.
struct BrdfUnderTest {
  std::function<double(const analytic::Dir3&, const analytic::Dir3&)> rho3;
  std::function<double(double, double)> rho2;
};

FurnaceSuite parse_furnace_suite(const nlohmann::json& j, const std::string& file);
FurnaceOutcome run_furnace_case(const FurnaceSuite& suite, const BrdfCase& c, const BrdfUnderTest& brdf = {});
// The suite as work items (item_work.h): one per case. samples > 0 overrides the suite's.
using FurnaceWork = ItemWork<FurnaceOutcome>;
Job<FurnaceWork> furnace_job(const FurnaceSuite& suite, long samples, nlohmann::json descriptor);
FurnaceRun furnace_run_from(const FurnaceSuite& suite, const std::vector<UnitResult<FurnaceWork>>& results);
nlohmann::json furnace_report_json(const FurnaceSuite& suite, const FurnaceRun& run);
void print_furnace_table(std::ostream& os, const FurnaceSuite& suite, const FurnaceRun& run);

}  // namespace vgroove::validation
