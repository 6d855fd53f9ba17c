#include "vgroove/validation/suite_kind.h"

#include "vgroove/support/user_error.h"
#include "vgroove/validation/kinds/kinds.h"

namespace vgroove::validation {

const std::vector<const SuiteKind*>& suite_kinds() {
  static const std::vector<const SuiteKind*> kinds = {
      &brdf_kind(),
      &table2_kind(),
      &furnace_kind(),
      &sampling_kind(),
      &nonsymmetric_kind(),
      &profiles_kind(),
      &groove_kind(),
      &energy_audit_kind(),
      &heightfield_kind(),
      &dielectric_grooves_kind(),
      &dielectric_brdf_kind(),
      &heightfield_albedo_kind(),
  };
  return kinds;
}

const SuiteKind& find_kind(const nlohmann::json& suite) {
  if (suite.is_object() && suite.contains("kind") && suite["kind"].is_string()) {
    const std::string name = suite["kind"].get<std::string>();
    for (const SuiteKind* k : suite_kinds())
      if (name == k->name()) return *k;
  }
  return groove_kind();
}

void check_rough_surface_overrides(const SuiteOverrides& o, const std::string& file, const std::string& kind) {
  if (o.sampling)
    throw support::UserError(o.names.sampling + " applies to single-groove suites; " + file + " (kind " + kind +
                             ") lands its rays at random points of the surface");
  if (o.eq6_form)
    throw support::UserError(o.names.eq6_form + " applies to single-groove suites; " + file + " (kind " + kind +
                             ") uses the corrected Eq. 6 throughout");
  if (o.rays) check_rays(*o.rays, o.names.rays);
  if (o.seed) check_seed(*o.seed, o.names.seed);
  if (o.model_table && kind != "brdf")
    throw support::UserError(o.names.model_table + " applies to suites of kind \"brdf\"; " + file + " is of kind " +
                             kind);
}

}  // namespace vgroove::validation
