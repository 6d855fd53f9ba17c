// The suite kind "profiles" (validation/profiles_suite.h: masking and multiple scattering on random profiles).
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"
#include "vgroove/validation/profiles_suite.h"

#include <algorithm>

namespace vgroove::validation {

namespace {

class ProfilesPlan final : public PlannedSuite {
 public:
  ProfilesPlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "profiles");
    suite_ = parse_profiles_suite(j, file);
    rays_ = o.rays.value_or(0);
    if (o.seed) suite_.seed = static_cast<std::uint64_t>(*o.seed);
  }
  std::string name() const override { return suite_.name; }
  std::string kind() const override { return "profiles"; }
  double memory_bytes(int threads, bool) const override { return profiles_run_memory_bytes(suite_, threads); }
  std::string memory_what(int threads) const override {
    return std::to_string(suite_.segments) + " segments per profile on each of " +
           std::to_string(std::min<std::size_t>(support::resolve_threads(threads), suite_.cases())) + " workers";
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const override {
    return suite_job(profiles_job(suite_, rays_, std::move(descriptor), cancel), suite_, profiles_run_from,
                     print_profiles_table, profiles_report_json);
  }

 private:
  ProfilesSuite suite_;
  long rays_ = 0;
};

}  // namespace

const SuiteKind& profiles_kind() {
  static const KindOf<ProfilesPlan> kind("profiles");
  return kind;
}

}  // namespace vgroove::validation
