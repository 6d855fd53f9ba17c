// vgroove Python module: what the bindings share. NumPy arrays in and out, user errors as
// ValueError, long work on a worker thread with the GIL released and Ctrl-C honoured.
#pragma once

#include "vgroove/analytic/brdf_model.h"
#include "vgroove/common/ndf_kind.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/brdf_suite.h"

#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace vgroove::python {

namespace py = pybind11;

// A one-dimensional C-contiguous array of doubles (any number-like input is converted).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// JSON (a report) as the Python objects json.loads gives for the file it is written to: dict,
// list, str, int, float, bool, None (also for NaN and infinity, which the file holds as null).
py::object to_python(const nlohmann::json& j);

NdfKind parse_ndf(const std::string& name);
// A model by the command line's name (analytic/brdf_model.h: "vgroove", "vgroove-nonsymmetric"
// when `nonsymmetric`, "cook-torrance"; "cook_torrance" too, this module's first spelling), else
// ValueError listing the names, as `vgroove brdf --model` does.
// The models of `vgroove brdf` (all: every one; else "vgroove" and "cook-torrance").
analytic::BrdfModel parse_brdf_model(const std::string& name, bool all);
validation::SurfaceDim parse_dim(const std::string& name);
// A Python int as a seed in [0, 2^63 - 1], else ValueError naming `what`.
long long to_seed(const py::handle& v, const std::string& what);
// A Python int as a count in [lo, hi], else ValueError naming `what`.
long long to_count(const py::handle& v, const std::string& what, long long lo, long long hi);
// alpha in the range of validation/ranges.h, [kMinAlpha, kMaxAlpha].
void check_alpha(double alpha);
// A conductor's Fresnel term, eta + i kappa (optics/fresnel.h), per reflection.
struct Conductor {
  double eta = 1.0, kappa = 0.0;
  analytic::FresnelFn fn() const;
};
// eta: a Python complex or real number eta + i kappa, eta in (0, kMaxFresnelEta], kappa in
// [0, kMaxFresnelKappa] (validation/ranges.h), else ValueError naming eta.
Conductor conductor_of(const py::object& eta);
// What vgroove.BRDF holds, checked as `vgroove brdf` checks its flags (one-line ValueErrors naming
// the argument): the model, NDF, roughness and dimension, the orders summed (max_k None: the model's
// default, analytic::default_max_k), the nonsymmetric model's alpha_y and partner law, and Fresnel
// (a conductor's eta; Walter's dielectric eta = n_far / n_near and G2).
struct BrdfSettings {
  analytic::BrdfModel model = analytic::BrdfModel::vgroove;
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;
  bool flat = false;
  int max_k = 0;
  bool max_k_given = false;
  double alpha_y = 0.0;  // 0: isotropic
  bool symmetric_partner = false;
  std::optional<Conductor> fresnel;
  double dielectric_eta = 1.5;
  analytic::MaskingKind masking = analytic::MaskingKind::smith_separable;
  analytic::BrdfEvalOptions options() const;
};
BrdfSettings brdf_settings(const std::string& model, const std::string& ndf, double alpha, const std::string& dim,
                           const py::object& max_k, const py::object& alpha_y, const py::object& partner,
                           const py::object& eta, const py::object& masking);
// The unit-vector rule of every direction the module takes: |len - 1| <= kUnitTolerance (and in
// flatland |y| <= kUnitTolerance). Directions normalized in float32 are off by ~6e-8.
inline constexpr double kUnitTolerance = 1e-6;
// Rows within kExactUnit of unit length are used as given (the command line's directions, bit for
// bit); the others within kUnitTolerance are divided by their length.
inline constexpr double kExactUnit = 1e-9;
// Directions n x 3 (rows of `w`, shape (n, 3)) held to the unit-vector rule: `w` itself when every
// row is within kExactUnit of unit length, else a copy with the other rows divided by their length.
// ValueError naming the first row of `what` that breaks the rule.
DoubleArray unit_directions(const DoubleArray& w, const char* what, bool flatland);
// Rows of directions n x 3 for a call over `n` items: one row (used for every item: a light shared
// by a batch costs one check and no copy) or n rows. ValueError naming `what` otherwise.
struct Rows {
  DoubleArray w;         // held to the unit-vector rule (unit_directions)
  std::size_t step = 3;  // doubles from one item's row to the next: 0 (one row for all) or 3
  const double* row(std::size_t j) const { return w.data() + j * step; }
};
Rows rows_of(const DoubleArray& w, const char* what, std::size_t n, bool flatland);
// The flatland angle of a direction in the plane y = 0: (-sin t, 0, cos t) -> t.
inline double flat_angle(const double* w) { return std::atan2(-w[0], w[2]); }

// Progress of one call, for a Python callable progress(done, total) (None: no reports). The work
// reports from any thread through fn() (support::ProgressFn: the counts are stored); the thread
// that holds the GIL passes them on with flush(), when they changed since the last call.
class ProgressRelay {
 public:
  explicit ProgressRelay(py::object callback = py::none()) : callback_(std::move(callback)) {
    if (!callback_.is_none() && !PyCallable_Check(callback_.ptr()))
      throw support::UserError("progress = " + py::repr(callback_).cast<std::string>() +
                               " must be a callable progress(done, total) or None");
  }
  bool active() const { return !callback_.is_none(); }
  void set(std::size_t done, std::size_t total) {
    std::lock_guard<std::mutex> lock(mu_);
    done_ = done, total_ = total;
  }
  // For the library's loops; empty without a callback (the loops then skip their reports).
  support::ProgressFn fn() {
    if (!active()) return {};
    return [this](std::size_t done, std::size_t total) { set(done, total); };
  }
  // The same for a loop over chunks of `unit` items, `items` in all: reports items.
  support::ProgressFn fn(std::size_t unit, std::size_t items) {
    if (!active()) return {};
    return [this, unit, items](std::size_t done, std::size_t) { set(std::min(items, done * unit), items); };
  }
  // With the GIL: progress(done, total) when the counts changed (exceptions propagate).
  void flush() {
    if (!active()) return;
    std::size_t d, t;
    {
      std::lock_guard<std::mutex> lock(mu_);
      d = done_, t = total_;
    }
    if (t == 0 || (d == last_done_ && t == last_total_)) return;
    last_done_ = d, last_total_ = t;
    callback_(d, t);
  }

 private:
  py::object callback_;
  std::mutex mu_;
  std::size_t done_ = 0, total_ = 0;
  std::size_t last_done_ = static_cast<std::size_t>(-1), last_total_ = static_cast<std::size_t>(-1);
};

// Runs work(cancel) (cancel: a std::atomic<bool>&, which the work may set too) on a worker thread with the GIL released
// while this thread polls Python's signal handlers every 50 ms: a KeyboardInterrupt (Ctrl-C) or any other exception a
// handler raises sets `cancel`, which the libraries check between chunks of work, and is raised here once the work has
// stopped. Exceptions thrown by the work are rethrown here (support::UserError becomes ValueError). Work that is known
// to be short runs inline (still without the GIL). With a relay, its counts are passed to the Python callback at each
// poll and once at the end (an exception from the callback stops the work as Ctrl-C does and is raised here).
template <class Work>
auto run_interruptible(Work&& work, bool short_work = false, ProgressRelay* relay = nullptr) {
  using R = decltype(work(std::declval<std::atomic<bool>&>()));
  std::atomic<bool> cancel{false};
  if (short_work) {
    std::optional<R> result;
    {
      py::gil_scoped_release release;
      result.emplace(work(cancel));
    }
    if (relay) relay->flush();
    return std::move(*result);
  }
  std::optional<R> result;
  std::exception_ptr error;
  bool signalled = false;
  std::optional<py::error_already_set> callback_error;
  {
    py::gil_scoped_release release;
    std::mutex mu;
    std::condition_variable cv;
    bool done = false;
    std::thread worker([&] {
      try {
        result.emplace(work(cancel));
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mu);
      done = true;
      cv.notify_one();
    });
    std::unique_lock<std::mutex> lock(mu);
    while (!done) {
      cv.wait_for(lock, std::chrono::milliseconds(50));
      if (done || signalled) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) signalled = true;
        if (!signalled && relay) {
          try {
            relay->flush();
          } catch (py::error_already_set& e) {
            callback_error.emplace(std::move(e));
            signalled = true;
          }
        }
      }
      if (signalled) cancel.store(true);
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (callback_error) throw std::move(*callback_error);
  if (signalled) throw py::error_already_set();
  if (error) std::rethrow_exception(error);
  if (relay) relay->flush();
  return std::move(*result);
}

// A new NumPy array of the given shape over memory allocated here (uninitialized, freed with the
// array). numpy.empty would madvise large arrays into transparent huge pages, which on a busy
// host can cost more kernel time than the work that fills them; plain allocations cost what the
// same outputs cost a C++ caller (bench/bindings_baseline_bench.cpp).
template <class T>
py::array_t<T> new_array(std::vector<py::ssize_t> shape) {
  std::size_t n = 1;
  for (py::ssize_t d : shape) n *= static_cast<std::size_t>(d);
  T* data = new T[std::max<std::size_t>(n, 1)];
  py::capsule owner(data, [](void* p) { delete[] static_cast<T*>(p); });
  return py::array_t<T>(shape, data, owner);
}

// A NumPy array of the given shape holding a copy of `data`.
template <class T>
py::array_t<T> array_of(const std::vector<T>& data, std::vector<py::ssize_t> shape) {
  py::array_t<T> a(shape);
  std::copy(data.begin(), data.end(), a.mutable_data());
  return a;
}

// A NumPy array of the given shape over `data`, moved (not copied) into memory the array owns:
// a lobe or tally of 10^8 cells is not held twice.
template <class T>
py::array_t<T> array_from(std::vector<T>&& data, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(data));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owned->data(), owner);
}

void bind_grooves(py::module_& m);
void bind_surfaces(py::module_& m);
void bind_brdfs(py::module_& m);
void bind_suites(py::module_& m);
void bind_sampling(py::module_& m);
void bind_energy(py::module_& m);

}  // namespace vgroove::python
