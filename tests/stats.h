// Statistics and quadrature for the tests, independent of the code under test: tanh-sinh
// quadrature, the chi-square survival function (Boost.Math) and a pooled chi-square
// goodness-of-fit test.
#pragma once

#include <boost/math/special_functions/gamma.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove::test_stats {

// Uniforms in (0, 1) from SplitMix64 on a counter: a stream independent of sim::Rng, so that a
// test's draws are not the code's own. Aggregate: Uniforms{seed}.
struct Uniforms {
  std::uint64_t state;
  double operator()() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return (static_cast<double>(z >> 11) + 0.5) * 0x1.0p-53;
  }
};

// Tanh-sinh (double exponential) quadrature of f over [a, b]: x = c + d tanh((pi/2) sinh t),
// trapezoidal in t with step h. The nodes crowd both ends doubly exponentially, so a peak at an
// end (split the range there) and integrable end singularities converge to near machine
// precision. A node's distance to its end is computed directly, not as a difference.
template <class F>
inline double tanh_sinh(F&& f, double a, double b, double h = 1.0 / 64.0) {
  const double c = 0.5 * (a + b), d = 0.5 * (b - a);
  double sum = 0.0;
  for (int k = -static_cast<int>(4.5 / h); k <= static_cast<int>(4.5 / h); ++k) {
    const double t = k * h;
    const double s = 0.5 * std::numbers::pi * std::sinh(t);
    const double ch = std::cosh(s);
    const double w = 0.5 * std::numbers::pi * std::cosh(t) / (ch * ch);
    if (!(w > 0.0)) continue;
    const double delta = d * 2.0 / (std::exp(2.0 * std::abs(s)) + 1.0);
    sum += w * f(k < 0 ? a + delta : (k > 0 ? b - delta : c));
  }
  return d * h * sum;
}

// Regularized upper incomplete gamma Q(a, x), from Boost.Math (not the library's
// validation/chi_square.h): the chi-square survival function is Q(dof/2, stat/2).
inline double gamma_q(double a, double x) { return x > 0.0 ? boost::math::gamma_q(a, x) : 1.0; }

struct ChiSquare {
  double stat = 0.0;
  int dof = 0;
  double p = 1.0;
  std::string table;  // the pooled cells, for the failure message
};

// Goodness of fit of observed counts to expected counts over bins [edges[j], edges[j+1]];
// adjacent bins are pooled until each cell expects at least 5 (a leftover joins the last cell).
inline ChiSquare chi_square_gof(const std::vector<double>& edges, const std::vector<double>& expected,
                                const std::vector<std::int64_t>& observed) {
  struct Cell {
    double lo, hi, e;
    std::int64_t o;
  };
  std::vector<Cell> cells;
  Cell acc{edges[0], edges[0], 0.0, 0};
  for (std::size_t j = 0; j < expected.size(); ++j) {
    acc.hi = edges[j + 1];
    acc.e += expected[j];
    acc.o += observed[j];
    if (acc.e >= 5.0) {
      cells.push_back(acc);
      acc = Cell{edges[j + 1], edges[j + 1], 0.0, 0};
    }
  }
  if (acc.e > 0.0 || acc.o > 0) {
    if (cells.empty())
      cells.push_back(acc);
    else {
      cells.back().hi = acc.hi;
      cells.back().e += acc.e;
      cells.back().o += acc.o;
    }
  }
  ChiSquare r;
  std::ostringstream os;
  os.precision(6);
  for (const Cell& c : cells) {
    r.stat += (c.o - c.e) * (c.o - c.e) / c.e;
    os << "  [" << c.lo << ", " << c.hi << "): expected " << c.e << ", observed " << c.o << "\n";
  }
  r.dof = static_cast<int>(cells.size()) - 1;  // the total is fixed
  r.p = gamma_q(0.5 * r.dof, 0.5 * r.stat);
  r.table = os.str();
  return r;
}

// Bin edges over (-pi/2, pi/2) equally spaced in slope/alpha, so each bin holds a comparable share
// of a distribution of roughness alpha (the outer edges exactly +-pi/2).
inline std::vector<double> slope_bin_edges(double alpha, int bins) {
  std::vector<double> edges(bins + 1);
  for (int j = 0; j <= bins; ++j)
    edges[j] = std::atan(alpha * std::tan(-0.5 * std::numbers::pi + j * std::numbers::pi / bins));
  edges.front() = -0.5 * std::numbers::pi;
  edges.back() = 0.5 * std::numbers::pi;
  return edges;
}

}  // namespace vgroove::test_stats
