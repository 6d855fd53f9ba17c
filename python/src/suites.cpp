// vgroove Python module: validate(path, **overrides), the library call that `vgroove validate`
// makes (validation/validate.h), returning the report as a dict.
#include "common.h"

#include "vgroove/validation/spec_lists.h"

#include "vgroove/validation/validate.h"

#include <iostream>

namespace vgroove::python {

namespace {

// path: the suite file; or, with suite_json (the suite as JSON text, from a dict), the name its
// messages give it. Progress: the work items of the run (cases, or chunks of them), per suite.
py::object validate(const std::string& path, const py::object& rays, int threads, std::optional<std::string> sampling,
                    std::optional<std::string> eq6_form, const py::object& seed, std::optional<std::string> model_table,
                    bool verbose, std::optional<std::string> suite_json, const py::object& progress) {
  validation::ValidateOptions o;
  o.names = validation::OptionNames::keywords();
  o.suite = path;
  nlohmann::json j;
  if (suite_json) {
    j = nlohmann::json::parse(*suite_json, nullptr, false);
    if (j.is_discarded()) throw support::UserError(path + ": is not JSON");
    o.suite_json = &j;
  }
  ProgressRelay relay(progress);
  if (!rays.is_none()) o.rays = static_cast<long>(to_count(rays, "rays", 1, validation::kMaxRays));
  o.threads = threads;
  o.sampling = std::move(sampling);
  o.eq6_form = std::move(eq6_form);
  if (!seed.is_none()) o.seed = to_seed(seed, "seed");
  o.model_table = std::move(model_table);
  const validation::ValidationPlan plan =
      run_interruptible([&](std::atomic<bool>&) { return validation::plan_validation(o); }, true);
  const validation::ProgressFactory factory = [&](const std::string&) { return relay.fn(); };
  const validation::ValidationResult res = run_interruptible(
      [&](std::atomic<bool>& cancel) {
        return validation::run_validation(plan, relay.active() ? factory : validation::ProgressFactory{}, &cancel);
      },
      false, &relay);
  if (verbose) py::print(res.table, py::arg("end") = "");
  return to_python(res.report);
}

}  // namespace

void bind_suites(py::module_& m) {
  m.def("validate", &validate, py::arg("path"), py::arg("rays"), py::arg("threads"), py::arg("sampling"),
        py::arg("eq6_form"), py::arg("seed"), py::arg("model_table"), py::arg("verbose"),
        py::arg("suite_json") = py::none(), py::arg("progress") = py::none());
}

}  // namespace vgroove::python
