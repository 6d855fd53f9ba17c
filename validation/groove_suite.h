// vgroove validation: a single-groove suite spec (Table 1, stress: grooves x theta_i, traced against
// Eq. 4-9 groove by groove), read strictly from JSON.
//
// Degrees at this edge only: the spec's *_deg values become radians in GrooveSuite.
#pragma once

#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"
#include "vgroove/sim/beam.h"
#include "vgroove/validation/ranges.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace vgroove::validation {

struct Thresholds {
  double max_l1;
  double mean_l1;
  double max_theta_o_error_rad;
};

// The paper's figures printed beside ours.
struct PaperFigures {
  std::string source;
  double max_l1;
  double mean_l1;
  // Which ray placement the paper's figures are consistent with, and the measurement that says so.
  std::string placement;
  std::string placement_evidence;
};

// How a suite's rays are cast; the same for every case.
struct CaseOptions {
  long rays = 1000;  // per lit facet (with breakpoint placement: the grid's rays M)
  sim::Sampling sampling = sim::Sampling::stratified;
  std::uint64_t seed = 1;
  int max_bounces = 100000;
  analytic::Eq6Form form = analytic::Eq6Form::corrected;
  // Also trace, per lit facet, the rays aimed exactly at the apex and at the rims (measure zero:
  // reported apart, never in the error) to show they are accounted for and yield no NaN.
  bool probe_vertices = false;
};

// One groove of a suite (radians). Symmetric grooves are given by theta_v; nonsymmetric ones by
// the facet normals' angles theta_l < 0 < theta_r (Lee et al. 2018, Fig. 5), with
// theta_v = pi + theta_l - theta_r.
struct GrooveParams {
  bool symmetric = true;
  double theta_v = 0.0;
  double theta_l = 0.0, theta_r = 0.0;
  // Zero aperture (theta_l = -90, theta_r = 90 deg: two parallel vertical walls meeting at the
  // apex): no opening, no light enters, the model is undefined. Reported, not compared.
  bool degenerate() const { return !(theta_v > 0.0); }
  static GrooveParams make_symmetric(double theta_v) { return {true, theta_v, 0.0, 0.0}; }
  static GrooveParams make_nonsymmetric(double theta_l, double theta_r) {
    return {false, std::numbers::pi + theta_l - theta_r, theta_l, theta_r};
  }
};

struct GrooveSuiteCase {
  GrooveParams groove;
  double theta_i = 0.0;  // radians
};

// The cases are the grid grooves x theta_i (groove outer), then the listed ones.
struct GrooveSuite {
  std::string file;
  std::string name;
  std::string description;
  std::vector<GrooveParams> grooves;
  std::vector<double> theta_i;  // radians
  std::vector<GrooveSuiteCase> listed;
  CaseOptions options;
  Thresholds thresholds;
  std::optional<PaperFigures> paper;
  std::size_t cases() const { return grooves.size() * theta_i.size() + listed.size(); }
  GrooveSuiteCase case_at(std::size_t c) const {
    const std::size_t grid = grooves.size() * theta_i.size();
    if (c < grid) return {grooves[c / theta_i.size()], theta_i[c % theta_i.size()]};
    return listed[c - grid];
  }
};

// A suite file, or a set of them: {"name", "description", "suites": ["a.json", ...]} with paths
// relative to the set's own file (data/suites/table1.json runs both columns of Table 1).
struct GrooveSuiteSet {
  std::string file;
  std::string name;
  std::string description;
  std::vector<GrooveSuite> suites;
};

GrooveSuite load_groove_suite(const std::string& file);
GrooveSuiteSet load_groove_suite_set(const std::string& file);
// The same from parsed JSON; `file` names it in messages (and anchors a set's relative paths).
GrooveSuite parse_groove_suite(const nlohmann::json& j, const std::string& file);
GrooveSuiteSet parse_groove_suite_set(const nlohmann::json& j, const std::string& file);

// The bounce limit a groove of aperture theta_v (radians) gets by default: kDefaultMaxBounces, or
// more when a narrower groove needs it: a ray in a wedge of aperture theta_v makes at most
// ceil(pi / theta_v) reflections, so with this limit every ray that can leave does.
int default_max_bounces(double theta_v);

// Range checks shared by the JSON and the command line (degrees in, UserError naming `what`).
void check_theta_v(double theta_v_deg, const std::string& what);
void check_theta_i(double theta_i_deg, const std::string& what);
void check_theta_l(double theta_l_deg, const std::string& what);
void check_theta_r(double theta_r_deg, const std::string& what);
// "[-89.999, 89.999]": the incident angles check_theta_i accepts.
std::string theta_i_range_text();

}  // namespace vgroove::validation
