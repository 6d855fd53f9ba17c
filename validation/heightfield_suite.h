// vgroove validation: the suite of kind "heightfield": random heightfields (sim/heightfield.h,
// Beckmann and GGX-slope fields, "aspect" (a number or a list): anisotropic Beckmann; "surface":
// "grooves": V-grooves at random orientations, sim/heightfield_grooves.h) traced exactly in 3D
// (heightfield_lobe.h), their lobes per k (rows 1, 2, 3+) and energies against the 3D Smith walk
// (analytic/smith_walk_3d.h, one per "walk_heights" distribution, side by side), Cook-Torrance with
// Smith's height-correlated G (k = 1) and the V-groove model (Eq. 16, analytic/lobe_3d.h; both
// skipped when anisotropic). Per case (ndf, aspect, alpha, theta_i): `fields` fields, `rays` rays on
// each; per cell the mean over the fields and its standard error. A model is within noise when
// every row's L1 <= expected + sigmas sd + tolerance and every E_k within sigmas se: measured, not
// a verdict. The verdict: no ray lost, every value finite, the `controls`. Optional "masking": G1,
// G2 per facet-normal bin against Smith's forms and the V-cavity, controls in the verdict. One work
// item per case; memory: one field per worker. Tests: tests/validation/heightfield_suite_test.cpp
// (HeightfieldSuite.*, HeightfieldSuiteCli.*, HeightfieldSuiteLong.*), tests/cluster/shards_test.sh.
// Schema: docs/schemas/suite.schema.json ($defs/heightfield). Derivation: docs/derivations/heightfield.md.
#pragma once

#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/smith_walk_3d.h"
#include "vgroove/sim/heightfield_masking.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/heightfield_lobe.h"
#include "vgroove/validation/item_work.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

// The rows compared: k = 1, 2 and every k >= 3.
inline constexpr int kHeightfieldRows = 3;

enum class HeightfieldModel : unsigned char { smith_walk, cook_torrance_smith, vgroove };
inline constexpr int kHeightfieldModels = 3;
const char* heightfield_model_name(HeightfieldModel m);  // "smith_walk", "cook_torrance_smith", "vgroove"

struct HeightfieldCase {
  analytic::NdfKind ndf = analytic::NdfKind::beckmann;
  double alpha = 0.5;
  double theta_i_deg = 0.0;
  double aspect = 1.0;  // alpha_y / alpha
};

struct HeightfieldControl {
  HeightfieldModel model = HeightfieldModel::smith_walk;
  std::size_t case_index = 0;
};

// The masking section (optional "masking" in the suite): per case (its theta_i, the light at
// azimuth 0) the traced G1(o) for each theta_o (sim/heightfield_masking.h, `points` points per
// field) and G2(i, o) for each theta_o x azimuth difference phi (o at azimuth phi), on the case's
// fields, per facet-normal bin (theta_m_bins over [0, 90) deg x phi_m_bins from o's azimuth (G1)
// or the bisector of i's and o's (G2)) and overall, against Smith's forms and the V-cavity
// (analytic/masking_shadowing.h). Its controls enter the verdict: a named model within noise for a
// case's G1(theta_o) or G2(theta_o, phi), overall or overall and in every bin.
struct HeightfieldMaskingControl {
  bool g2 = false;
  std::string
      model;  // G1: smith, vcavity; G2: smith_separable, ..._height_correlated, ..._direction_correlated, vcavity
  std::size_t case_index = 0, theta_o_index = 0, phi_index = 0;  // phi: G2 only
  bool every_bin = false;
};
struct HeightfieldMaskingSpec {
  std::vector<double> theta_o_deg, phi_deg;
  long points = 20000;  // per field, theta_o and pair
  int theta_m_bins = 3, phi_m_bins = 4;
  std::vector<HeightfieldMaskingControl> controls;
  std::size_t pairs() const { return theta_o_deg.size() * phi_deg.size(); }
  int bins() const { return theta_m_bins * phi_m_bins; }
};

struct HeightfieldSuite {
  std::string file, name, description;
  std::vector<analytic::NdfKind> ndfs;
  std::vector<double> alphas;
  std::vector<double> theta_i_deg;
  HeightfieldSurfaceKind surface = HeightfieldSurfaceKind::gaussian;  // "surface" (default gaussian)
  int field_size = 256;
  double correlation_length = 8.0;  // grooves: 3 l long and apart (groove_field_options)
  // "aspect": alpha_y / alpha (Beckmann Gaussian fields; alpha is alpha_x), one number or a list
  // (cases over them). A case with aspect != 1: the walk takes alpha_x, alpha_y; Cook-Torrance and
  // the V-groove model (isotropic here) are skipped; a suite with one refuses the masking section.
  std::vector<double> aspects{1.0};
  bool aspect_list = false;  // given as a list (the report echoes the form given)
  bool anisotropic() const {
    return std::any_of(aspects.begin(), aspects.end(), [](double a) { return a != 1.0; });
  }
  // "walk_heights": the Smith walk once per height distribution (Heitz et al. 2016, Sec. 4), the
  // first the walk the controls and the tables hold (default log C1, the walk before the key).
  std::vector<analytic::WalkHeights> walk_heights{analytic::WalkHeights::log_c1};
  int fields = 4;
  long rays = 20000;         // per field and case
  long walk_paths = 200000;  // per case
  int theta_bins = 9, phi_bins = 8;
  std::uint64_t seed = 1;
  double sigmas = 5.0;
  double model_tolerance = 1e-4;  // added to every L1 threshold (the integrated models' target error)
  std::vector<HeightfieldControl> controls;
  std::optional<HeightfieldMaskingSpec> masking;
  std::size_t cases() const { return ndfs.size() * aspects.size() * alphas.size() * theta_i_deg.size(); }
  HeightfieldCase case_at(std::size_t c) const;  // order: ndf, aspect, alpha, theta_i (innermost)
  int bins() const { return theta_bins * phi_bins; }
};

// One model against the traced lobe, per compared row (Cook-Torrance: k = 1 only).
struct HeightfieldMiss {
  std::vector<double> l1, l1_expected, l1_threshold;                         // per row: the L1 of the joint fractions
  std::vector<double> energy, energy_diff, energy_threshold;                 // per row: the model's E_k, traced - model
  double l1_total = 0.0, l1_total_expected = 0.0, l1_total_threshold = 0.0;  // the rows together
  bool within_noise = false;
};

// One masking model against a traced G (overall and per bin; the bins with points on every
// field): traced - model, and in units of the traced standard error. Within noise when the overall
// and every bin's |traced - model| <= sigmas se + tolerance (a result, not a verdict).
struct HeightfieldMaskingMiss {
  std::string model;
  double value = 0.0;        // the model's overall G
  std::vector<double> bins;  // per bin (Smith's forms: the same value)
  double diff = 0.0, z = 0.0;
  int worst_bin = -1;  // the bin furthest in units of its se (-1: none compared)
  double worst_bin_diff = 0.0, worst_bin_z = 0.0;
  bool overall_within_noise = false, within_noise = false;
};
template <class F>
void fields(HeightfieldMaskingMiss& m, F&& f) {
  f("model", m.model), f("value", m.value), f("bins", m.bins), f("diff", m.diff), f("z", m.z);
  f("worst_bin", m.worst_bin), f("worst_bin_diff", m.worst_bin_diff), f("worst_bin_z", m.worst_bin_z);
  f("overall_within_noise", m.overall_within_noise), f("within_noise", m.within_noise);
}

// A traced G (G1 at theta_o, or G2 at theta_i, theta_o, phi) over the fields: the mean of the
// fields' values and its standard error (their spread, at least the points' binomial error), per
// bin (NaN where a field had no point) and overall.
struct HeightfieldMaskingValue {
  double theta_o_deg = 0.0, phi_deg = 0.0;
  double g = 0.0, g_se = 0.0;
  std::vector<double> bins, bins_se;
  std::vector<std::int64_t> bin_points;  // front-facing points per bin over the fields
  double g1_i = 0.0, g1_o = 0.0;         // G2 only: the two G1s under G2's weight (means)
  std::vector<HeightfieldMaskingMiss> models;
};
template <class F>
void fields(HeightfieldMaskingValue& v, F&& f) {
  f("theta_o_deg", v.theta_o_deg), f("phi_deg", v.phi_deg), f("g", v.g), f("g_se", v.g_se), f("bins", v.bins);
  f("bins_se", v.bins_se), f("bin_points", v.bin_points), f("g1_i", v.g1_i), f("g1_o", v.g1_o);
  f("models", v.models);
}

// The walk of one more height distribution (walk_heights[1..]) against the traced lobe and against
// the first distribution's walk (both sides with their multinomial errors).
struct HeightfieldOtherWalk {
  std::string heights;
  std::int64_t paths = 0, left = 0;
  std::vector<double> lobe, energy;
  HeightfieldMiss against_traced, against_first;
};
struct HeightfieldOutcome {
  HeightfieldCase c;
  std::int64_t rays = 0, lost = 0, bounce_limit = 0, edge_hits = 0, vertex_hits = 0, bounces = 0;
  std::vector<double> lobe, lobe_se;      // traced joint fractions, rows k = 1, 2, 3+ (row by row)
  std::vector<double> energy, energy_se;  // traced E_k per row
  double albedo = 0.0, albedo_se = 0.0;
  std::vector<double> walk_lobe, walk_energy;  // the first of walk_heights
  std::int64_t walk_paths = 0, walk_left = 0;
  std::vector<HeightfieldOtherWalk> other_walks;  // walk_heights[1..]
  std::vector<double> ct_lobe;                    // k = 1 row
  double ct_error = 0.0;                          // the integration's error estimate
  std::vector<double> vgroove_lobe, vgroove_energy;
  HeightfieldMiss walk, cook_torrance, vgroove;
  std::vector<HeightfieldMaskingValue> g1, g2;  // the masking section: per theta_o; per (theta_o, phi)
  std::int64_t masking_points = 0, masking_lost = 0;
  double masking_s = 0.0;
  double field_s = 0.0, trace_s = 0.0, walk_s = 0.0, model_s = 0.0;
  bool non_finite = false;
  bool pass = false;
};

template <class F>
void fields(HeightfieldMiss& m, F&& f) {
  f("l1", m.l1), f("l1_expected", m.l1_expected), f("l1_threshold", m.l1_threshold), f("energy", m.energy);
  f("energy_diff", m.energy_diff), f("energy_threshold", m.energy_threshold), f("l1_total", m.l1_total);
  f("l1_total_expected", m.l1_total_expected), f("l1_total_threshold", m.l1_total_threshold);
  f("within_noise", m.within_noise);
}
template <class F>
void fields(HeightfieldOtherWalk& w, F&& f) {
  f("heights", w.heights), f("paths", w.paths), f("left", w.left), f("lobe", w.lobe), f("energy", w.energy);
  f("against_traced", w.against_traced), f("against_first", w.against_first);
}
template <class F>
void fields(HeightfieldOutcome& o, F&& f) {
  f("rays", o.rays), f("lost", o.lost), f("bounce_limit", o.bounce_limit), f("edge_hits", o.edge_hits);
  f("vertex_hits", o.vertex_hits), f("bounces", o.bounces), f("lobe", o.lobe), f("lobe_se", o.lobe_se);
  f("energy", o.energy), f("energy_se", o.energy_se), f("albedo", o.albedo), f("albedo_se", o.albedo_se);
  f("walk_lobe", o.walk_lobe), f("walk_energy", o.walk_energy), f("walk_paths", o.walk_paths);
  f("walk_left", o.walk_left), f("ct_lobe", o.ct_lobe), f("ct_error", o.ct_error);
  f("vgroove_lobe", o.vgroove_lobe), f("vgroove_energy", o.vgroove_energy), f("walk", o.walk);
  f("cook_torrance", o.cook_torrance), f("vgroove", o.vgroove), f("field_s", o.field_s), f("trace_s", o.trace_s);
  f("walk_s", o.walk_s), f("model_s", o.model_s), f("non_finite", o.non_finite), f("pass", o.pass);
  f("g1", o.g1), f("g2", o.g2), f("masking_points", o.masking_points), f("masking_lost", o.masking_lost);
  f("masking_s", o.masking_s), f("other_walks", o.other_walks);
}

struct HeightfieldRun {
  std::vector<HeightfieldOutcome> cases;
  std::vector<bool> controls_hold;          // per suite control
  std::vector<bool> masking_controls_hold;  // per masking control
  int threads = 1;
  double wall_s = 0.0;
  bool interrupted = false;
  bool pass = false;
};

HeightfieldSuite parse_heightfield_suite(const nlohmann::json& j, const std::string& file);
// One field with its hierarchy per worker (min(threads, cases)) and the synthesis' peak, plus
// every case's lobes. Throws support::UserError ("FILE: /field_size: ...", one line) when a
// field does not fit this process's share of memory.
double heightfield_run_memory_bytes(const HeightfieldSuite& suite, int threads);

using HeightfieldWork = ItemWork<HeightfieldOutcome>;
// rays > 0 overrides the suite's rays per field.
Job<HeightfieldWork> heightfield_job(const HeightfieldSuite& suite, long rays, nlohmann::json descriptor,
                                     const std::atomic<bool>* cancel = nullptr);
HeightfieldOutcome run_heightfield_case(const HeightfieldSuite& suite, std::size_t case_index, long rays,
                                        const std::atomic<bool>* cancel = nullptr);
HeightfieldRun heightfield_run_from(const HeightfieldSuite& suite,
                                    const std::vector<UnitResult<HeightfieldWork>>& results);
HeightfieldRun run_heightfield_suite(const HeightfieldSuite& suite, long rays, int threads,
                                     const support::ProgressFn& progress = {},
                                     const std::atomic<bool>* cancel = nullptr);

// A model against a traced lobe (rows x bins joint fractions with their standard errors and the
// per-row energies with theirs): `rows` rows compared from the first; model_var per bin (may be
// empty: none), model_energy_var per row likewise.
HeightfieldMiss heightfield_miss(const std::vector<double>& lobe, const std::vector<double>& lobe_se,
                                 const std::vector<double>& energy, const std::vector<double>& energy_se,
                                 const std::vector<double>& model, const std::vector<double>& model_var,
                                 const std::vector<double>& model_energy, const std::vector<double>& model_energy_var,
                                 int rows, int bins, double sigmas, double tolerance);

// The masking section of one field (validation/heightfield_suite_masking.cpp): per theta_o its
// G1 tally, per pair its G2 tally, appended to the per-field lists; then the means over the fields
// and the models. Seeds from the suite's seed, the case and the field.
struct HeightfieldMaskingFields {
  std::vector<std::vector<sim::HeightfieldMaskingTally>> g1;       // [theta_o][field]
  std::vector<std::vector<sim::HeightfieldJointMaskingTally>> g2;  // [pair][field]
};
void trace_masking_field(const HeightfieldSuite& suite, std::size_t case_index, int field,
                         const sim::HeightfieldSurface& s, HeightfieldMaskingFields& out,
                         const std::atomic<bool>* cancel);
void finish_masking(const HeightfieldSuite& suite, const HeightfieldMaskingFields& traced, HeightfieldOutcome& out);
// A model (its overall value and per-bin values) against a traced value: HeightfieldMaskingMiss.
HeightfieldMaskingMiss heightfield_masking_miss(const std::string& name, const HeightfieldMaskingValue& traced,
                                                double value, std::vector<double> bins, double sigmas,
                                                double tolerance);
// The masking spec from the suite's "masking" object (theta_o_deg within [0, 89.9], phi_deg
// within [0, 180], points, bins, controls naming a case of `suite` and a measured theta_o, phi).
HeightfieldMaskingSpec parse_heightfield_masking(support::JsonObject& m, const HeightfieldSuite& suite);
// A masking control's miss in a case's outcome (nullptr where the outcome lacks it: an interrupted
// run) and whether it holds; the controls in the report and the table.
const HeightfieldMaskingMiss* masking_control_miss(const HeightfieldMaskingControl& c, const HeightfieldOutcome& o);
bool masking_control_holds(const HeightfieldMaskingControl& c, const HeightfieldOutcome& o);
nlohmann::json masking_controls_json(const HeightfieldSuite& suite, const HeightfieldRun& run);
void print_masking_controls(std::ostream& os, const HeightfieldSuite& suite, const HeightfieldRun& run);

nlohmann::json heightfield_report_json(const HeightfieldSuite& suite, const HeightfieldRun& run);
void print_heightfield_table(std::ostream& os, const HeightfieldSuite& suite, const HeightfieldRun& run);

}  // namespace vgroove::validation
