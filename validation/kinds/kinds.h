// vgroove validation: the suite kinds (suite_kind.h), one file each in this folder, and what they
// share beyond the job (job_of.h): the table and verdict as a SuiteResult.
#pragma once

#include "vgroove/validation/suite_kind.h"

#include <cstdint>
#include <sstream>
#include <string>

namespace vgroove::validation {

const SuiteKind& groove_kind();              // single grooves: Table 1, stress, sets of suites (groove_kind.cpp)
const SuiteKind& brdf_kind();                // "brdf": Fig. 11; with a model table, a foreign model (brdf_kind.cpp)
const SuiteKind& table2_kind();              // "table2" (table2_kind.cpp)
const SuiteKind& furnace_kind();             // "furnace" (furnace_kind.cpp)
const SuiteKind& sampling_kind();            // "sampling" (sampling_kind.cpp)
const SuiteKind& nonsymmetric_kind();        // "nonsymmetric_brdf" (nonsymmetric_kind.cpp)
const SuiteKind& profiles_kind();            // "profiles" (profiles_kind.cpp)
const SuiteKind& energy_audit_kind();        // "energy_audit" (energy_audit_kind.cpp)
const SuiteKind& heightfield_kind();         // "heightfield" (heightfield_kind.cpp)
const SuiteKind& heightfield_albedo_kind();  // "heightfield_albedo" (heightfield_albedo_kind.cpp)
const SuiteKind& dielectric_grooves_kind();  // "dielectric_grooves" (dielectric_grooves_kind.cpp)
const SuiteKind& dielectric_brdf_kind();     // "dielectric_brdf" (dielectric_brdf_kind.cpp)

// The result of a finished run: `print(std::ostream&)` writes its table, `report_json()` (called
// only when `report`) builds its report.
template <class Print, class Report>
SuiteResult suite_result(bool pass, bool report, Print&& print, Report&& report_json) {
  SuiteResult r;
  std::ostringstream table;
  print(table);
  r.table = table.str();
  if (report) r.report = report_json();
  r.pass = pass;
  return r;
}

// What the plans of the rough-surface kinds share: the suite, the rays override (0: the suite's)
// and the seed override applied to the suite.
template <class Suite>
class SuitePlan : public PlannedSuite {
 public:
  std::string name() const override { return suite_.name; }

 protected:
  void apply_rays_and_seed(const SuiteOverrides& o) {
    rays_ = o.rays.value_or(0);
    if (o.seed) suite_.seed = static_cast<std::uint64_t>(*o.seed);
  }
  Suite suite_;
  long rays_ = 0;
};

// A kind object for a PlannedSuite type P whose constructor reads (json, file, overrides).
template <class P>
class KindOf final : public SuiteKind {
 public:
  explicit KindOf(const char* name) : name_(name) {}
  const char* name() const override { return name_; }
  std::unique_ptr<PlannedSuite> plan(const nlohmann::json& j, const std::string& file,
                                     const SuiteOverrides& o) const override {
    return std::make_unique<P>(j, file, o);
  }

 private:
  const char* name_;
};

}  // namespace vgroove::validation
