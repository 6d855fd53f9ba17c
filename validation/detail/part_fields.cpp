#include "vgroove/validation/detail/part_fields.h"

#include "vgroove/support/format.h"
#include "vgroove/validation/partial_report.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vgroove::validation {

namespace {

// Sums of counts: up to 10^8 bins of up to 2^62 each do not overflow 128 bits.
__extension__ using Wide = __int128;
std::string wide_text(Wide v) {
  if (v >= std::numeric_limits<std::int64_t>::min() && v <= std::numeric_limits<std::int64_t>::max())
    return std::to_string(static_cast<std::int64_t>(v));
  return std::to_string(static_cast<long double>(v));
}

const nlohmann::json& array_of(support::JsonObject& o, const std::string& key, std::size_t n) {
  const nlohmann::json& a = o.raw(key);
  if (!a.is_array()) o.fail(key, "= " + support::value_text(a) + " must be an array");
  if (a.size() != n)
    o.fail(key, "has " + std::to_string(a.size()) + " entries, not the " + std::to_string(n) + " the job's bins need");
  return a;
}

std::int64_t count_at(const support::JsonObject& o, const std::string& key, const nlohmann::json& v, std::size_t i,
                      std::int64_t hi) {
  if (!v.is_number_integer()) o.fail_at(key, i, "= " + support::value_text(v) + " must be an integer count");
  if (v.is_number_unsigned() ? v.get<std::uint64_t>() > static_cast<std::uint64_t>(hi)
                             : (v.get<std::int64_t>() < 0 || v.get<std::int64_t>() > hi))
    o.fail_at(key, i, "= " + support::value_text(v) + " is out of range [0, " + std::to_string(hi) + "]");
  return v.get<std::int64_t>();
}

bool exact_text(const nlohmann::json& v) {
  return v.is_number() || (v.is_string() && (v == "nan" || v == "inf" || v == "-inf"));
}
const char* const kExactWhat = " must be a number (or \"nan\", \"inf\", \"-inf\")";
const char* const kFractionWhat = " is out of range [0, 1] (a fraction of the incident flux, to the model's accuracy)";

bool fraction(double x, double excess) { return x >= -excess && x <= 1.0 + excess; }

// Two sums of the same n non-negative values, in any order, differ by at most 2 n eps their size.
bool same_sum(double sum, double total, std::size_t n) {
  const double scale = std::max(std::fabs(sum), std::fabs(total));
  return std::fabs(sum - total) <= 2.0 * static_cast<double>(n + 1) * std::numeric_limits<double>::epsilon() * scale;
}

}  // namespace

std::vector<std::int64_t> read_counts(support::JsonObject& o, const std::string& key, std::size_t n, std::int64_t hi) {
  const nlohmann::json& a = array_of(o, key, n);
  std::vector<std::int64_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = count_at(o, key, a[i], i, hi);
  return v;
}

double read_exact_double(support::JsonObject& o, const std::string& key) {
  const nlohmann::json& v = o.raw(key);
  if (!exact_text(v)) o.fail(key, "= " + support::value_text(v) + kExactWhat);
  return exact_double(v);
}

std::vector<double> read_exact_doubles(support::JsonObject& o, const std::string& key, std::size_t n) {
  const nlohmann::json& a = array_of(o, key, n);
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!exact_text(a[i])) o.fail_at(key, i, "= " + support::value_text(a[i]) + kExactWhat);
    v[i] = exact_double(a[i]);
  }
  return v;
}

double read_fraction(support::JsonObject& o, const std::string& key, double excess) {
  const double x = read_exact_double(o, key);
  if (!fraction(x, excess)) o.fail(key, "= " + support::value_text(o.raw(key)) + kFractionWhat);
  return x;
}

std::vector<double> read_fractions(support::JsonObject& o, const std::string& key, std::size_t n, double excess) {
  std::vector<double> v = read_exact_doubles(o, key, n);
  const nlohmann::json& a = o.raw(key);
  for (std::size_t i = 0; i < n; ++i)
    if (!fraction(v[i], excess)) o.fail_at(key, i, "= " + support::value_text(a[i]) + kFractionWhat);
  return v;
}

void check_model_sum(const support::JsonObject& o, const std::string& key, const std::vector<double>& v, double total,
                     const std::string& total_key) {
  double sum = 0.0;
  for (double x : v) sum += x;
  if (!same_sum(sum, total, v.size()))
    o.fail(key, "sums to " + support::format("%.17g", sum) + ", not " + total_key + " = " +
                    support::format("%.17g", total) + " (up to rounding)");
}

void check_model_margins(const support::JsonObject& o, const std::string& key, const std::vector<double>& joint,
                         const std::vector<double>& by_row, const std::string& row_key,
                         const std::vector<double>& by_bin, const std::string& bin_key) {
  const std::size_t bins = by_bin.size();
  std::vector<double> rows(by_row.size(), 0.0), cols(bins, 0.0);
  for (std::size_t r = 0; r < by_row.size(); ++r)
    for (std::size_t b = 0; b < bins; ++b) rows[r] += joint[r * bins + b], cols[b] += joint[r * bins + b];
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (!same_sum(rows[r], by_row[r], bins))
      o.fail(key, "row " + std::to_string(r) + " sums to " + support::format("%.17g", rows[r]) + ", but " + row_key +
                      "/" + std::to_string(r) + " = " + support::format("%.17g", by_row[r]) + " (up to rounding)");
  for (std::size_t b = 0; b < bins; ++b)
    if (!same_sum(cols[b], by_bin[b], by_row.size()))
      o.fail(key, "bin " + std::to_string(b) + " sums to " + support::format("%.17g", cols[b]) +
                      " over its rows, but " + bin_key + "/" + std::to_string(b) + " = " +
                      support::format("%.17g", by_bin[b]) + " (up to rounding)");
}

void read_fates(support::JsonObject& o, sim::RayFates& t, std::int64_t rays, std::int64_t max_bounces) {
  t.rays = o.integer("rays", rays, rays);
  t.escaped = o.integer("escaped", 0, rays);
  t.blocked = o.integer("blocked", 0, rays);
  t.vertex_hits = o.integer("vertex_hits", 0, rays);
  t.bounce_limit = o.integer("bounce_limit", 0, rays);
  t.not_upward = o.integer("not_upward", 0, rays);
  // The buckets are each <= rays <= 2^62, so their sum cannot overflow.
  if (t.escaped + t.lost() != rays)
    o.fail("escaped", "+ blocked + vertex_hits + bounce_limit + not_upward = " + std::to_string(t.escaped + t.lost()) +
                          ", not the " + std::to_string(rays) + " rays");
  t.max_k_seen = static_cast<int>(o.integer("max_k_seen", 0, t.escaped > 0 ? max_bounces : 0));
  const long double most = static_cast<long double>(t.escaped) * t.max_k_seen;
  t.bounces = o.integer("bounces", t.escaped > 0 ? t.max_k_seen : 0,
                        most > static_cast<long double>(std::numeric_limits<std::int64_t>::max())
                            ? std::numeric_limits<std::int64_t>::max()
                            : static_cast<std::int64_t>(most));
}

sim::BounceCounts read_bounce_counts(support::JsonObject& o, int max_k, std::int64_t rays, std::int64_t max_bounces) {
  sim::BounceCounts t(max_k);
  read_fates(o, t, rays, max_bounces);
  t.by_k = read_counts(o, "by_k", static_cast<std::size_t>(max_k) + 2, t.escaped);
  check_sum(o, "by_k", t.by_k, t.escaped, "escaped rays");
  return t;
}

void check_sum(const support::JsonObject& o, const std::string& key, const std::vector<std::int64_t>& v,
               std::int64_t total, const std::string& what) {
  Wide sum = 0;
  for (std::int64_t x : v) sum += x;
  if (sum != total) o.fail(key, "sums to " + wide_text(sum) + ", not the " + std::to_string(total) + " " + what);
}

void check_margins(const support::JsonObject& o, const std::string& key, const std::vector<std::int64_t>& joint,
                   const std::vector<std::int64_t>& by_row, const std::string& row_key,
                   const std::vector<std::int64_t>& by_bin, const std::string& bin_key) {
  const std::size_t bins = by_bin.size();
  std::vector<Wide> rows(by_row.size(), 0), cols(bins, 0);
  for (std::size_t r = 0; r < by_row.size(); ++r)
    for (std::size_t b = 0; b < bins; ++b) rows[r] += joint[r * bins + b], cols[b] += joint[r * bins + b];
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (rows[r] != by_row[r])
      o.fail(key, "row " + std::to_string(r) + " sums to " + wide_text(rows[r]) + ", but " + row_key + "/" +
                      std::to_string(r) + " = " + std::to_string(by_row[r]));
  for (std::size_t b = 0; b < bins; ++b)
    if (cols[b] != by_bin[b])
      o.fail(key, "bin " + std::to_string(b) + " sums to " + wide_text(cols[b]) + " over its rows, but " + bin_key +
                      "/" + std::to_string(b) + " = " + std::to_string(by_bin[b]));
}

}  // namespace vgroove::validation
