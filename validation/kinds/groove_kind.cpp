// Single-groove suites (validation/groove_suite.h: Table 1, stress; a set of suites in one report), the
// kind of every suite file whose "kind" is not another registered kind's.
#include "vgroove/validation/groove_suite_run.h"
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"
#include "vgroove/validation/report.h"

namespace vgroove::validation {

namespace {

class GroovePlan final : public PlannedSuite {
 public:
  GroovePlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    if (o.model_table)
      throw support::UserError(o.names.model_table +
                               " applies to suites of kind \"brdf\" (e.g. data/suites/fig11.json); " + file +
                               " is a single-groove suite");
    set_ = parse_groove_suite_set(j, file);
    for (const GrooveSuite& suite : set_.suites)
      opts_.push_back(options_with_overrides(suite, o.rays, o.sampling, o.eq6_form, o.seed, o.names));
  }
  std::string name() const override { return set_.name; }
  std::string kind() const override { return "single-groove"; }
  std::vector<std::string> extra_inputs() const override {
    std::vector<std::string> files;
    for (const GrooveSuite& s : set_.suites)
      if (s.file != set_.file) files.push_back(s.file);
    return files;
  }
  double memory_bytes(int threads, bool report) const override {
    double memory = 0.0;
    for (std::size_t n = 0; n < set_.suites.size(); ++n)
      memory += groove_suite_memory_bytes(set_.suites[n], opts_[n], threads, report);
    return memory;
  }
  std::string memory_what(int) const override {
    std::size_t cases = 0;
    for (const GrooveSuite& s : set_.suites) cases += s.cases();
    return std::to_string(cases) + " cases";
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const override {
    auto job = groove_cases_job(set_.suites, opts_, std::move(descriptor));
    job.work.cancel = cancel;
    GrooveCaseWork work = job.work;
    return job_of(std::move(job),
                  [set = set_, work = std::move(work)](const auto& results, int threads, double wall, bool report) {
                    const std::vector<GrooveSuiteRun> runs = groove_suite_runs_from(work, results, threads, wall);
                    bool pass = true;
                    for (const GrooveSuiteRun& r : runs) pass = pass && r.summary.pass();
                    return suite_result(
                        pass, report, [&](std::ostream& os) { print_set_table(os, set, runs); },
                        [&] { return report_json(set, runs); });
                  });
  }

 private:
  GrooveSuiteSet set_;
  std::vector<CaseOptions> opts_;
};

}  // namespace

const SuiteKind& groove_kind() {
  static const KindOf<GroovePlan> kind("single-groove");
  return kind;
}

}  // namespace vgroove::validation
