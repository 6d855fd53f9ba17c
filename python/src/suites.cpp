// vgroove Python module: validate(path, **overrides), the library call that `vgroove validate`
// makes (validation/validate.h), returning the report as a dict.
#include "common.h"

#include "vgroove/validation/spec_lists.h"

#include "vgroove/validation/validate.h"

#include <iostream>

namespace vgroove::python {

namespace {

py::object validate(const std::string& path, const py::object& rays, int threads, std::optional<std::string> sampling,
                    std::optional<std::string> eq6_form, const py::object& seed, std::optional<std::string> model_table,
                    bool verbose) {
  validation::ValidateOptions o;
  o.names = validation::OptionNames::keywords();
  o.suite = path;
  if (!rays.is_none()) o.rays = static_cast<long>(to_count(rays, "rays", 1, validation::kMaxRays));
  o.threads = threads;
  o.sampling = std::move(sampling);
  o.eq6_form = std::move(eq6_form);
  if (!seed.is_none()) o.seed = to_seed(seed, "seed");
  o.model_table = std::move(model_table);
  const validation::ValidationPlan plan =
      run_interruptible([&](std::atomic<bool>&) { return validation::plan_validation(o); }, true);
  const validation::ValidationResult res =
      run_interruptible([&](std::atomic<bool>& cancel) { return validation::run_validation(plan, {}, &cancel); });
  if (verbose) py::print(res.table, py::arg("end") = "");
  return to_python(res.report);
}

}  // namespace

void bind_suites(py::module_& m) {
  m.def("validate", &validate, py::arg("path"), py::arg("rays"), py::arg("threads"), py::arg("sampling"),
        py::arg("eq6_form"), py::arg("seed"), py::arg("model_table"), py::arg("verbose"));
}

}  // namespace vgroove::python
