// vgroove Python module: single V-grooves. The model (Eq. 4-9) vectorized over arrays of angles,
// one beam traced exactly with every ray's fate, and one validation case (a Table 1 cell).
#include "common.h"

#include "vgroove/validation/spec_lists.h"

#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"
#include "vgroove/common/angles.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/run_options.h"
#include "vgroove/validation/single_groove.h"

#include <cmath>
#include <optional>

namespace vgroove::python {

namespace {

using validation::GrooveParams;
using validation::OptionNames;

const OptionNames& names() {
  static const OptionNames n = OptionNames::keywords();
  return n;
}

std::string indexed(const std::string& what, std::size_t j, std::size_t n) {
  return n == 1 ? what : what + "[" + std::to_string(j) + "]";
}

// The model for cases j of flat, equally long arrays (the Python side broadcasts them): per facet
// lit, k, f_a, shadow; per facet and zone (up to four) n, G, the fraction of the beam entering the
// opening and theta_o (degrees, not rounded).
py::dict kaleidoscope(DoubleArray theta_i_deg, std::optional<DoubleArray> theta_v_deg,
                      std::optional<DoubleArray> theta_l_deg, std::optional<DoubleArray> theta_r_deg,
                      const std::string& eq6_form) {
  const analytic::Eq6Form form = validation::parse_form(eq6_form, names().eq6_form);
  const bool nonsym = theta_l_deg.has_value();
  const std::size_t n = static_cast<std::size_t>(theta_i_deg.size());
  const double* ti = theta_i_deg.data();
  const double* v = theta_v_deg ? theta_v_deg->data() : nullptr;
  const double* l = nonsym ? theta_l_deg->data() : nullptr;
  const double* r = nonsym ? theta_r_deg->data() : nullptr;
  // Checked before any work; a bad element is named with its index (the names are built only then).
  std::vector<GrooveParams> grooves(n);
  for (std::size_t j = 0; j < n; ++j) {
    try {
      grooves[j] = nonsym ? validation::groove_from_degrees(std::nullopt, l[j], r[j], names())
                          : validation::groove_from_degrees(v[j], std::nullopt, std::nullopt, names());
      validation::check_theta_i(ti[j], names().theta_i);
    } catch (const support::UserError&) {
      OptionNames nm = names();
      nm.theta_v = indexed(nm.theta_v, j, n), nm.theta_l = indexed(nm.theta_l, j, n);
      nm.theta_r = indexed(nm.theta_r, j, n);
      if (nonsym)
        validation::groove_from_degrees(std::nullopt, l[j], r[j], nm);
      else
        validation::groove_from_degrees(v[j], std::nullopt, std::nullopt, nm);
      validation::check_theta_i(ti[j], indexed(names().theta_i, j, n));
      throw;
    }
  }
  const auto sn = static_cast<py::ssize_t>(n);
  auto lit = new_array<bool>({sn, 2});
  auto k = new_array<int>({sn, 2});
  auto f_a = new_array<double>({sn, 2}), shadow = new_array<double>({sn, 2});
  auto zn = new_array<int>({sn, 2, 4});
  auto G = new_array<double>({sn, 2, 4}), frac = new_array<double>({sn, 2, 4}), theta_o = new_array<double>({sn, 2, 4});
  bool* plit = lit.mutable_data();
  int* pk = k.mutable_data();
  int* pn = zn.mutable_data();
  double *pfa = f_a.mutable_data(), *psh = shadow.mutable_data(), *pG = G.mutable_data(), *pfr = frac.mutable_data(),
         *pto = theta_o.mutable_data();
  run_interruptible(
      [&](std::atomic<bool>& cancel) {
        for (std::size_t j = 0; j < n; ++j) {
          if ((j & 0xffff) == 0 && cancel.load(std::memory_order_relaxed)) break;
          const double theta_i = ti[j] * kRadPerDeg;
          validation::ModelShares m[2];
          for (int f = 0; f < 2; ++f)
            m[f] = validation::model_shares(grooves[j], theta_i, static_cast<sim::Side>(f), form);
          // The fractions of the beam entering the opening, as `analytic` gives them (sum to 1).
          const double width = validation::entering_width(m);
          for (int f = 0; f < 2; ++f) {
            const std::size_t a = 2 * j + static_cast<std::size_t>(f);
            plit[a] = m[f].lit, pk[a] = m[f].lit ? m[f].k : 0;
            pfa[a] = m[f].lit ? m[f].f_a : 0.0, psh[a] = m[f].lit ? m[f].shadow : 0.0;
            for (int z = 0; z < 4; ++z) {
              const std::size_t b = 4 * a + static_cast<std::size_t>(z);
              const bool used = m[f].lit && z < m[f].shares;
              pn[b] = used ? m[f].share[z].n : 0;
              pG[b] = used ? m[f].share[z].G : 0.0;
              pfr[b] = used ? m[f].share[z].G * m[f].f_a / width : 0.0;
              pto[b] = used ? m[f].share[z].theta_o * kDegPerRad : 0.0;
            }
          }
        }
        return 0;
      },
      n < 100000);
  py::dict d;
  d["lit"] = lit, d["k"] = k, d["f_a"] = f_a, d["shadow"] = shadow;
  d["n"] = zn, d["G"] = G, d["fraction"] = frac, d["theta_o_deg"] = theta_o;
  return d;
}

GrooveParams groove_of(std::optional<double> v, std::optional<double> l, std::optional<double> r) {
  return validation::groove_from_degrees(v, l, r, names());
}

py::object analytic_json(double theta_i_deg, std::optional<double> v, std::optional<double> l, std::optional<double> r,
                         const std::string& eq6_form) {
  const GrooveParams g = groove_of(v, l, r);
  validation::check_theta_i(theta_i_deg, names().theta_i);
  const analytic::Eq6Form form = validation::parse_form(eq6_form, names().eq6_form);
  return to_python(validation::analytic_json(g, theta_i_deg, form));
}

// The bounce limit: max_bounces, or (None) the command line's default for the groove
// (validation::default_max_bounces: enough for every ray of a narrow groove to leave).
int check_max_bounces(const py::handle& v, const GrooveParams& g) {
  if (v.is_none()) return g.degenerate() ? validation::kDefaultMaxBounces : validation::default_max_bounces(g.theta_v);
  return static_cast<int>(to_count(v, "max_bounces", 1, validation::kMaxBounces));
}

// Every ray of one beam: landing point x on the rim line, facet hit first (0 left, 1 right, -1
// none), bounce count, fate (0 escaped, 1 blocked, 2 vertex hit, 3 bounce limit), exit direction
// and theta_o (degrees; 0 where the ray did not escape), and the command line's summary.
py::dict trace(double theta_i_deg, const py::object& rays_obj, std::optional<double> v, std::optional<double> l,
               std::optional<double> r, const std::string& sampling_name, const py::object& seed_obj,
               const py::object& max_bounces_obj) {
  const GrooveParams g = groove_of(v, l, r);
  validation::check_theta_i(theta_i_deg, names().theta_i);
  const long rays = static_cast<long>(to_count(rays_obj, "rays", 1, validation::kMaxRays));
  const sim::Sampling sampling = validation::parse_sampling(sampling_name, names().sampling);
  const long long seed = to_seed(seed_obj, "seed");
  const int max_bounces = check_max_bounces(max_bounces_obj, g);
  const auto n = static_cast<py::ssize_t>(rays);
  auto x = new_array<double>({n}), theta_o = new_array<double>({n}), exit_dir = new_array<double>({n, 2});
  auto first = new_array<std::int8_t>({n}), fate = new_array<std::int8_t>({n});
  auto k = new_array<std::int32_t>({n});
  double *px = x.mutable_data(), *pto = theta_o.mutable_data(), *pd = exit_dir.mutable_data();
  std::int8_t *pf = first.mutable_data(), *pfate = fate.mutable_data();
  std::int32_t* pk = k.mutable_data();
  const sim::Tally tally = run_interruptible(
      [&](std::atomic<bool>& cancel) {
        sim::Tally t;
        const bool done = validation::trace_beam_rays(
            g, theta_i_deg * kRadPerDeg, rays, sampling, static_cast<std::uint64_t>(seed), max_bounces,
            [&](long j0, int m, const double* xs, const sim::TraceResult* res) {
              for (int j = 0; j < m; ++j) {
                const sim::TraceResult& rr = res[j];
                const std::size_t a = static_cast<std::size_t>(j0 + j);
                t.add(rr);
                const bool esc = rr.how == sim::Termination::escaped;
                px[a] = xs[j];
                pf[a] = rr.bounces > 0 ? static_cast<std::int8_t>(rr.first) : std::int8_t{-1};
                pk[a] = rr.bounces;
                pfate[a] = static_cast<std::int8_t>(rr.how);
                pd[2 * a] = esc ? rr.exit_dir.x() : 0.0, pd[2 * a + 1] = esc ? rr.exit_dir.y() : 0.0;
                pto[a] = esc ? sim::angle_from_normal(rr.exit_dir) * kDegPerRad : 0.0;
              }
            },
            &cancel);
        (void)done;
        return t;
      },
      rays < 100000);
  py::dict d;
  d["x"] = x, d["first_facet"] = first, d["k"] = k, d["fate"] = fate, d["exit_dir"] = exit_dir;
  d["theta_o_deg"] = theta_o;
  d["summary"] = to_python(validation::trace_json(g, theta_i_deg, rays, sampling, seed, max_bounces, tally));
  return d;
}

py::object groove_case(double theta_i_deg, std::optional<double> v, std::optional<double> l, std::optional<double> r,
                       const py::object& rays_obj, const std::string& sampling_name, const py::object& seed_obj,
                       const py::object& max_bounces_obj, const std::string& eq6_form, bool probe_vertices,
                       const py::object& stream_obj) {
  const GrooveParams g = groove_of(v, l, r);
  validation::check_theta_i(theta_i_deg, names().theta_i);
  validation::CaseOptions o;
  o.rays = static_cast<long>(to_count(rays_obj, "rays", 1, validation::kMaxRays));
  o.sampling = validation::parse_sampling(sampling_name, names().sampling);
  o.seed = static_cast<std::uint64_t>(to_seed(seed_obj, "seed"));
  o.max_bounces = check_max_bounces(max_bounces_obj, g);
  o.form = validation::parse_form(eq6_form, names().eq6_form);
  o.probe_vertices = probe_vertices;
  const auto stream = static_cast<std::uint64_t>(to_seed(stream_obj, "stream"));
  const validation::CaseOutcome c = run_interruptible(
      [&](std::atomic<bool>&) { return validation::run_case(g, theta_i_deg * kRadPerDeg, o, stream); },
      o.rays < 100000);
  return to_python(validation::case_json(c));
}

}  // namespace

void bind_grooves(py::module_& m) {
  m.def("kaleidoscope", &kaleidoscope, py::arg("theta_i_deg"), py::arg("theta_v_deg"), py::arg("theta_l_deg"),
        py::arg("theta_r_deg"), py::arg("eq6_form"));
  m.def("analytic", &analytic_json, py::arg("theta_i_deg"), py::arg("theta_v_deg"), py::arg("theta_l_deg"),
        py::arg("theta_r_deg"), py::arg("eq6_form"));
  m.def("trace", &trace, py::arg("theta_i_deg"), py::arg("rays"), py::arg("theta_v_deg"), py::arg("theta_l_deg"),
        py::arg("theta_r_deg"), py::arg("sampling"), py::arg("seed"), py::arg("max_bounces"));
  m.def("groove_case", &groove_case, py::arg("theta_i_deg"), py::arg("theta_v_deg"), py::arg("theta_l_deg"),
        py::arg("theta_r_deg"), py::arg("rays"), py::arg("sampling"), py::arg("seed"), py::arg("max_bounces"),
        py::arg("eq6_form"), py::arg("probe_vertices"), py::arg("stream"));
}

}  // namespace vgroove::python
