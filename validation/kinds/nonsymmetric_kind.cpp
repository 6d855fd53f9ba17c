// The suite kind "nonsymmetric_brdf" (validation/nonsymmetric_suite.h: Lee et al. 2018, Sec. 5.2-5.3).
#include "vgroove/validation/kinds/kinds.h"
#include "vgroove/validation/kinds/one_process_job.h"
#include "vgroove/validation/nonsymmetric_suite.h"

namespace vgroove::validation {

namespace {

class NonsymmetricPlan final : public PlannedSuite {
 public:
  NonsymmetricPlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "nonsymmetric_brdf");
    suite_ = parse_nonsymmetric_suite(j, file);
    rays_ = o.rays.value_or(0);
    if (o.seed) suite_.seed = static_cast<std::uint64_t>(*o.seed);
  }
  std::string name() const override { return suite_.name; }
  std::string kind() const override { return "nonsymmetric_brdf"; }
  double memory_bytes(int, bool) const override { return 0.0; }
  std::string memory_what(int threads) const override {
    (void)threads;
    return std::string();
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>*) const override {
    return one_process_job(
        std::move(descriptor), suite_.file + " (kind nonsymmetric_brdf)",
        [s = suite_, rays = rays_](int threads, const support::ProgressFn& progress, const std::atomic<bool>* cancel,
                                   bool report) -> std::optional<SuiteResult> {
          NonsymmetricRun run = run_nonsymmetric_suite(s, rays, threads, progress, cancel);
          if (run.interrupted) return std::nullopt;
          return suite_result(
              run.pass, report, [&](std::ostream& os) { print_nonsymmetric_table(os, s, run); },
              [&] { return nonsymmetric_report_json(s, run); });
        });
  }

 private:
  NonsymmetricSuite suite_;
  long rays_ = 0;
};

}  // namespace

const SuiteKind& nonsymmetric_kind() {
  static const KindOf<NonsymmetricPlan> kind("nonsymmetric_brdf");
  return kind;
}

}  // namespace vgroove::validation
