// vgroove validation: a shard part's tallies read as strictly as a suite file.
//
// `vgroove merge` and MPI rank 0 read tallies written by other processes. Every value is read
// through support::JsonObject (file and JSON pointer in each message), and checked against what
// the job says the tally must be: every array's length against the suite's bins and rows, every
// count a non-negative integer no larger than the rays of the chunks the part ran, and the sums
// consistent (the fates add up to the rays, the bounce rows and histogram bins to the escaped
// rays, each row and bin of the joint histogram to its margins). A tally that breaks any of these
// is a UserError naming the part and the path; nothing damaged reaches a report. A part's model
// values (its fixed part) are read as strictly: fractions of the flux in [0, 1], totals that hold.
// Test: tests/cluster/merge_parts_test.py (every mutation of real parts refused or harmless).
#pragma once

#include "vgroove/sim/ndf_grooves.h"
#include "vgroove/sim/ray_fates.h"
#include "vgroove/support/json_reader.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vgroove::validation {

// An array of exactly n integers, each in [0, hi].
std::vector<std::int64_t> read_counts(support::JsonObject& o, const std::string& key, std::size_t n, std::int64_t hi);
// A double as partial_report.h's exact_json writes it (a number, or "nan", "inf", "-inf").
double read_exact_double(support::JsonObject& o, const std::string& key);
// An array of exactly n such doubles.
std::vector<double> read_exact_doubles(support::JsonObject& o, const std::string& key, std::size_t n);

// The fates of `rays` rays: "rays" equal to it, every bucket in [0, rays] and their sum `rays`,
// "bounces" and "max_k_seen" possible for the escaped rays (none when none escaped; at most
// max_k_seen each, and max_k_seen at least once) with at most `max_bounces` reflections a ray.
void read_fates(support::JsonObject& o, sim::RayFates& t, std::int64_t rays, std::int64_t max_bounces);

// read_fates, and "by_k": the escaped rays by bounce count in max_k + 2 rows (sim::BounceCounts).
sim::BounceCounts read_bounce_counts(support::JsonObject& o, int max_k, std::int64_t rays, std::int64_t max_bounces);

// Fails naming `key` unless the values of v sum to `total` (`what` names the total).
void check_sum(const support::JsonObject& o, const std::string& key, const std::vector<std::int64_t>& v,
               std::int64_t total, const std::string& what);
// joint[row * bins + bin] (rows x bins): each row sums to by_row[row] and each bin to by_bin[bin].
void check_margins(const support::JsonObject& o, const std::string& key, const std::vector<std::int64_t>& joint,
                   const std::vector<std::int64_t>& by_row, const std::string& row_key,
                   const std::vector<std::int64_t>& by_bin, const std::string& bin_key);

// A part's model values (its fixed part: the analytic side, not recomputed at merge) are fractions
// of the incident flux, each in [0, 1] to the model's accuracy (analytic/albedo_vgroove.h: 1e-9):
// a total of many quadrature terms may pass 1, a remainder (the row k > max_k) fall below 0
// (-5e-16 seen), by that much, never by more.
inline constexpr double kModelExcess = 1e-9;
// An exact double (read_exact_double) in [-excess, 1 + excess]: finite.
double read_fraction(support::JsonObject& o, const std::string& key, double excess = kModelExcess);
// An array of exactly n such fractions.
std::vector<double> read_fractions(support::JsonObject& o, const std::string& key, std::size_t n,
                                   double excess = kModelExcess);
// Fails naming `key` unless v sums to `total` (o's `total_key`) up to the rounding of summing
// non-negative values in any order: |sum - total| <= 2 n eps max(sum, total).
void check_model_sum(const support::JsonObject& o, const std::string& key, const std::vector<double>& v, double total,
                     const std::string& total_key);
// joint[row * bins + bin]: each row sums to by_row[row] and each bin to by_bin[bin] up to rounding.
void check_model_margins(const support::JsonObject& o, const std::string& key, const std::vector<double>& joint,
                         const std::vector<double>& by_row, const std::string& row_key,
                         const std::vector<double>& by_bin, const std::string& bin_key);

}  // namespace vgroove::validation
