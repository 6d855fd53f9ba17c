// vgroove validation: a suite spec, read strictly from JSON.
//
// Degrees at this edge only: the spec's *_deg values become radians in Suite.
#pragma once

#include "analytic/kaleidoscope.h"
#include "sim/beam.h"

#include <cstdint>
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
};

// How a suite's rays are cast; the same for every case.
struct CaseOptions {
  long rays = 1000;  // per lit facet
  sim::Sampling sampling = sim::Sampling::stratified;
  std::uint64_t seed = 1;
  int max_bounces = 100000;
  analytic::Eq6Form form = analytic::Eq6Form::corrected;
};

struct Suite {
  std::string file;
  std::string name;
  std::string description;
  std::vector<double> theta_v;  // radians
  std::vector<double> theta_i;  // radians
  CaseOptions options;
  Thresholds thresholds;
  std::optional<PaperFigures> paper;
  std::size_t cases() const { return theta_v.size() * theta_i.size(); }
};

Suite load_suite(const std::string& file);

// Range checks shared by the JSON and the command line (radians in, UserError naming `what`).
void check_theta_v(double theta_v_deg, const std::string& what);
void check_theta_i(double theta_i_deg, const std::string& what);

}  // namespace vgroove::validation
