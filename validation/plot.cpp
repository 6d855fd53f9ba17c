#include "vgroove/validation/plot.h"

#include "vgroove/support/user_error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>
#include <vector>

namespace vgroove::validation {

namespace {

struct Point {
  double wall_s, max_l1, mean_l1;
  long rays;
};

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// Decades that cover [lo, hi] (both > 0).
std::pair<double, double> log_range(double lo, double hi) {
  return {std::floor(std::log10(lo)), std::ceil(std::log10(hi))};
}

}  // namespace

std::string accuracy_svg(const nlohmann::json& report, const std::string& file) {
  if (!report.is_object() || !report.contains("runs") || !report["runs"].is_array() || report["runs"].empty())
    throw support::UserError(file +
                             ": not an accuracy report (no /runs): make one with `vgroove bench accuracy ... --out`");
  std::map<std::string, std::vector<Point>> lines;
  double tmin = INFINITY, tmax = 0, emin = INFINITY, emax = 0;
  for (std::size_t n = 0; n < report["runs"].size(); ++n) {
    const auto& r = report["runs"][n];
    try {
      const Point p{r.at("wall_s").get<double>(), r.at("max_l1").get<double>(), r.at("mean_l1").get<double>(),
                    r.at("rays_per_facet").get<long>()};
      if (!(p.wall_s > 0 && p.max_l1 > 0 && p.mean_l1 > 0)) continue;  // log axes: nothing to draw at 0
      lines[r.at("sampling").get<std::string>()].push_back(p);
      tmin = std::min(tmin, p.wall_s), tmax = std::max(tmax, p.wall_s);
      emin = std::min(emin, p.mean_l1), emax = std::max(emax, p.max_l1);
    } catch (const nlohmann::json::exception& e) {
      throw support::UserError(file + ": /runs/" + std::to_string(n) + " is not an accuracy run: " + e.what());
    }
  }
  if (lines.empty()) throw support::UserError(file + ": no run with positive wall time and error to plot");
  // Plain variables, not structured bindings: clang 14 cannot capture those in the lambdas below.
  double tx0, tx1, ey0, ey1;
  std::tie(tx0, tx1) = log_range(tmin, tmax);
  std::tie(ey0, ey1) = log_range(emin, emax);
  const double W = 720, H = 480, L = 80, R = 160, T = 48, B = 60;
  auto X = [&](double t) { return L + (std::log10(t) - tx0) / std::max(1.0, tx1 - tx0) * (W - L - R); };
  auto Y = [&](double e) { return H - B - (std::log10(e) - ey0) / std::max(1.0, ey1 - ey0) * (H - T - B); };
  std::string svg =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"720\" height=\"480\" font-family=\"sans-serif\" "
      "font-size=\"12\">\n";
  svg += "<rect width=\"720\" height=\"480\" fill=\"white\"/>\n";
  const std::string title = "L1 error against wall time: " + report.value("suite", std::string("?"));
  const std::string made_by =
      "vgroove " + report.value("version", std::string("?")) + ", git " + report.value("git", std::string("?")) + ", " +
      std::to_string(report.value("threads", 0)) + " threads, seed " + std::to_string(report.value("seed", 0ULL));
  svg += "<text x=\"" + fmt("%.0f", L) + "\" y=\"20\" font-size=\"14\">" + title + "</text>\n";
  svg += "<text x=\"" + fmt("%.0f", L) + "\" y=\"34\" font-size=\"10\" fill=\"#555\">" + made_by + "</text>\n";
  // Axes with a grid line per decade.
  for (double d = tx0; d <= tx1; d += 1) {
    const double x = X(std::pow(10.0, d));
    svg += "<line x1=\"" + fmt("%.1f", x) + "\" y1=\"" + fmt("%.1f", T) + "\" x2=\"" + fmt("%.1f", x) + "\" y2=\"" +
           fmt("%.1f", H - B) + "\" stroke=\"#ddd\"/>\n";
    svg += "<text x=\"" + fmt("%.1f", x) + "\" y=\"" + fmt("%.1f", H - B + 18) + "\" text-anchor=\"middle\">1e" +
           fmt("%.0f", d) + "</text>\n";
  }
  for (double d = ey0; d <= ey1; d += 1) {
    const double y = Y(std::pow(10.0, d));
    svg += "<line x1=\"" + fmt("%.1f", L) + "\" y1=\"" + fmt("%.1f", y) + "\" x2=\"" + fmt("%.1f", W - R) + "\" y2=\"" +
           fmt("%.1f", y) + "\" stroke=\"#ddd\"/>\n";
    svg += "<text x=\"" + fmt("%.1f", L - 8) + "\" y=\"" + fmt("%.1f", y + 4) + "\" text-anchor=\"end\">1e" +
           fmt("%.0f", d) + "</text>\n";
  }
  svg += "<text x=\"" + fmt("%.1f", (L + W - R) / 2) + "\" y=\"" + fmt("%.1f", H - 16) +
         "\" text-anchor=\"middle\">wall time (s)</text>\n";
  svg += "<text x=\"20\" y=\"" + fmt("%.1f", (T + H - B) / 2) + "\" transform=\"rotate(-90 20 " +
         fmt("%.1f", (T + H - B) / 2) + ")\" text-anchor=\"middle\">L1 error</text>\n";
  const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd"};
  int c = 0, legend = 0;
  for (auto& [sampling, pts] : lines) {
    std::sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) { return a.wall_s < b.wall_s; });
    const std::string color = colors[c++ % 4];
    for (int which = 0; which < 2; ++which) {
      std::string path;
      for (const Point& p : pts)
        path +=
            (path.empty() ? "M" : " L") + fmt("%.1f", X(p.wall_s)) + "," + fmt("%.1f", Y(which ? p.mean_l1 : p.max_l1));
      svg += "<path d=\"" + path + "\" fill=\"none\" stroke=\"" + color + "\" stroke-width=\"2\"" +
             (which ? " stroke-dasharray=\"6 4\"" : "") + "/>\n";
      for (const Point& p : pts) {
        const double x = X(p.wall_s), y = Y(which ? p.mean_l1 : p.max_l1);
        svg += "<circle cx=\"" + fmt("%.1f", x) + "\" cy=\"" + fmt("%.1f", y) + "\" r=\"3\" fill=\"" + color + "\"/>\n";
        if (!which)
          svg += "<text x=\"" + fmt("%.1f", x + 5) + "\" y=\"" + fmt("%.1f", y - 5) +
                 "\" font-size=\"10\">N=" + std::to_string(p.rays) + "</text>\n";
      }
      const double ly = T + 20 + 18 * legend++;
      svg += "<line x1=\"" + fmt("%.1f", W - R + 10) + "\" y1=\"" + fmt("%.1f", ly) + "\" x2=\"" +
             fmt("%.1f", W - R + 34) + "\" y2=\"" + fmt("%.1f", ly) + "\" stroke=\"" + color + "\" stroke-width=\"2\"" +
             (which ? " stroke-dasharray=\"6 4\"" : "") + "/>\n";
      svg += "<text x=\"" + fmt("%.1f", W - R + 40) + "\" y=\"" + fmt("%.1f", ly + 4) + "\">" + sampling +
             (which ? " mean" : " max") + "</text>\n";
    }
  }
  svg += "</svg>\n";
  return svg;
}

std::string cost_svg(const nlohmann::json& report) {
  if (!report.contains("cost_vs_theta_v") || !report["cost_vs_theta_v"].contains("points") ||
      !report["cost_vs_theta_v"]["points"].is_array())
    return {};
  struct C {
    double v, tracer, model;
  };
  std::vector<C> c;
  for (const auto& p : report["cost_vs_theta_v"]["points"])
    if (p.is_object() && p.value("theta_v_deg", 0.0) > 0 && p.value("tracer_ns_per_ray", 0.0) > 0 &&
        p.value("model_ns_per_eval", 0.0) > 0)
      c.push_back(
          {p["theta_v_deg"].get<double>(), p["tracer_ns_per_ray"].get<double>(), p["model_ns_per_eval"].get<double>()});
  if (c.empty()) return {};
  double vmin = INFINITY, vmax = 0, nmin = INFINITY, nmax = 0;
  for (const auto& q : c) {
    vmin = std::min(vmin, q.v), vmax = std::max(vmax, q.v);
    nmin = std::min({nmin, q.tracer, q.model}), nmax = std::max({nmax, q.tracer, q.model});
  }
  // Plain variables, not structured bindings: clang 14 cannot capture those in the lambdas below.
  double vx0, vx1, ny0, ny1;
  std::tie(vx0, vx1) = log_range(vmin, vmax);
  std::tie(ny0, ny1) = log_range(nmin, nmax);
  const double W = 720, H = 420, L = 80, R = 190, T = 48, B = 60;
  auto X = [&](double v) { return L + (std::log10(v) - vx0) / std::max(1.0, vx1 - vx0) * (W - L - R); };
  auto Y = [&](double n) { return H - B - (std::log10(n) - ny0) / std::max(1.0, ny1 - ny0) * (H - T - B); };
  std::string svg =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"720\" height=\"420\" font-family=\"sans-serif\" "
      "font-size=\"12\">\n";
  svg += "<rect width=\"720\" height=\"420\" fill=\"white\"/>\n";
  svg +=
      "<text x=\"80\" y=\"20\" font-size=\"14\">Cost against aperture: one traced ray vs one model evaluation</text>\n";
  svg += "<text x=\"80\" y=\"34\" font-size=\"10\" fill=\"#555\">vgroove " + report.value("version", std::string("?")) +
         ", git " + report.value("git", std::string("?")) +
         "; one thread, theta_i = " + fmt("%.0f", report["cost_vs_theta_v"].value("theta_i_deg", 0.0)) +
         " deg</text>\n";
  for (double d = vx0; d <= vx1; d += 1) {
    const double x = X(std::pow(10.0, d));
    svg += "<line x1=\"" + fmt("%.1f", x) + "\" y1=\"" + fmt("%.1f", T) + "\" x2=\"" + fmt("%.1f", x) + "\" y2=\"" +
           fmt("%.1f", H - B) + "\" stroke=\"#ddd\"/>\n";
    svg += "<text x=\"" + fmt("%.1f", x) + "\" y=\"" + fmt("%.1f", H - B + 18) + "\" text-anchor=\"middle\">" +
           fmt("%g", std::pow(10.0, d)) + "</text>\n";
  }
  for (double d = ny0; d <= ny1; d += 1) {
    const double y = Y(std::pow(10.0, d));
    svg += "<line x1=\"" + fmt("%.1f", L) + "\" y1=\"" + fmt("%.1f", y) + "\" x2=\"" + fmt("%.1f", W - R) + "\" y2=\"" +
           fmt("%.1f", y) + "\" stroke=\"#ddd\"/>\n";
    svg += "<text x=\"" + fmt("%.1f", L - 8) + "\" y=\"" + fmt("%.1f", y + 4) + "\" text-anchor=\"end\">" +
           fmt("%g", std::pow(10.0, d)) + "</text>\n";
  }
  svg += "<text x=\"" + fmt("%.1f", (L + W - R) / 2) + "\" y=\"" + fmt("%.1f", H - 16) +
         "\" text-anchor=\"middle\">theta_v (deg)</text>\n";
  svg += "<text x=\"20\" y=\"" + fmt("%.1f", (T + H - B) / 2) + "\" transform=\"rotate(-90 20 " +
         fmt("%.1f", (T + H - B) / 2) + ")\" text-anchor=\"middle\">ns</text>\n";
  const char* color[2] = {"#1f77b4", "#d62728"};
  const char* label[2] = {"tracer, per ray", "model Eq. 4-6, per eval."};
  for (int which = 0; which < 2; ++which) {
    std::string path;
    for (const auto& q : c)
      path += (path.empty() ? "M" : " L") + fmt("%.1f", X(q.v)) + "," + fmt("%.1f", Y(which ? q.model : q.tracer));
    svg += "<path d=\"" + path + "\" fill=\"none\" stroke=\"" + color[which] + "\" stroke-width=\"2\"/>\n";
    for (const auto& q : c)
      svg += "<circle cx=\"" + fmt("%.1f", X(q.v)) + "\" cy=\"" + fmt("%.1f", Y(which ? q.model : q.tracer)) +
             "\" r=\"3\" fill=\"" + color[which] + "\"/>\n";
    const double ly = T + 20 + 18 * which;
    svg += "<line x1=\"" + fmt("%.1f", W - R + 10) + "\" y1=\"" + fmt("%.1f", ly) + "\" x2=\"" +
           fmt("%.1f", W - R + 34) + "\" y2=\"" + fmt("%.1f", ly) + "\" stroke=\"" + color[which] +
           "\" stroke-width=\"2\"/>\n";
    svg += "<text x=\"" + fmt("%.1f", W - R + 40) + "\" y=\"" + fmt("%.1f", ly + 4) + "\" font-size=\"10\">" +
           label[which] + "</text>\n";
  }
  svg += "</svg>\n";
  return svg;
}

bool is_brdf_report(const nlohmann::json& report) {
  return report.is_object() && report.value("kind", std::string()) == "brdf" && report.contains("cases");
}

std::vector<std::pair<std::string, std::string>> brdf_grid_svgs(const nlohmann::json& report, const std::string& file) {
  if (!is_brdf_report(report) || !report["cases"].is_array() || report["cases"].empty())
    throw support::UserError(
        file +
        ": not a brdf suite report (no /cases): make one with `vgroove validate data/suites/fig11.json --out R`");
  // Group the cases by (ndf, dimension); within a group, columns by alpha, rows by theta_i.
  struct Panel {
    double alpha, theta_i;
    const nlohmann::json* c;
  };
  std::map<std::string, std::vector<Panel>> groups;
  std::vector<std::string> order;
  for (std::size_t n = 0; n < report["cases"].size(); ++n) {
    const auto& c = report["cases"][n];
    try {
      if (!c.contains("plane")) continue;
      const std::string key = c.at("ndf").get<std::string>() + "-" + c.at("dimension").get<std::string>();
      if (!groups.count(key)) order.push_back(key);
      groups[key].push_back({c.at("alpha").get<double>(), c.at("theta_i_deg").get<double>(), &c});
    } catch (const nlohmann::json::exception& e) {
      throw support::UserError(file + ": /cases/" + std::to_string(n) + " is not a brdf case: " + e.what());
    }
  }
  if (groups.empty()) throw support::UserError(file + ": no case with a lobe on the plane of incidence to plot");
  const std::string made_by = "vgroove " + report.value("version", std::string("?")) + ", git " +
                              report.value("git", std::string("?")) + ", seed " +
                              std::to_string(report.value("seed", 0ULL));
  const char* k_colors[] = {"#1f77b4", "#ff7f0e", "#9467bd", "#8c564b"};
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& key : order) {
    const auto& panels = groups[key];
    std::vector<double> alphas, thetas;
    for (const auto& p : panels) {
      if (std::find(alphas.begin(), alphas.end(), p.alpha) == alphas.end()) alphas.push_back(p.alpha);
      if (std::find(thetas.begin(), thetas.end(), p.theta_i) == thetas.end()) thetas.push_back(p.theta_i);
    }
    std::sort(alphas.begin(), alphas.end());
    std::sort(thetas.begin(), thetas.end());
    const double PW = 260, PH = 170, M = 40, TOP = 60;
    const double W = M + PW * alphas.size() + 20, H = TOP + PH * thetas.size() + 30;
    std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fmt("%.0f", W) + "\" height=\"" +
                      fmt("%.0f", H) + "\" font-family=\"sans-serif\" font-size=\"10\">\n";
    svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg += "<text x=\"" + fmt("%.0f", M) + "\" y=\"18\" font-size=\"14\">" + report.value("suite", std::string("?")) +
           ": " + key +
           " (bars: traced; red: analytic, bin-integrated; dashed: k = 1..4; black dotted: Cook-Torrance)</text>\n";
    svg += "<text x=\"" + fmt("%.0f", M) + "\" y=\"32\" fill=\"#555\">" + made_by +
           "; x: theta_o on the plane of incidence, -90..90 deg (negative: mirror side); y: " +
           panels.front().c->at("plane").value("unit", std::string("density")) + "</text>\n";
    for (const auto& p : panels) {
      const std::size_t col =
          static_cast<std::size_t>(std::find(alphas.begin(), alphas.end(), p.alpha) - alphas.begin());
      const std::size_t row =
          static_cast<std::size_t>(std::find(thetas.begin(), thetas.end(), p.theta_i) - thetas.begin());
      const double x0 = M + PW * col + 8, y0 = TOP + PH * row + 8, w = PW - 16, h = PH - 28;
      const auto& pl = p.c->at("plane");
      const auto th = pl.at("theta_deg").get<std::vector<double>>();
      const auto sim = pl.at("sim").get<std::vector<double>>();
      const auto model = pl.at("model").get<std::vector<double>>();
      const auto ct = pl.at("cook_torrance").get<std::vector<double>>();
      double ymax = 0.0;
      for (std::size_t n = 0; n < th.size(); ++n) ymax = std::max({ymax, sim[n], model[n]});
      if (!(ymax > 0)) ymax = 1.0;
      auto X = [&](double deg) { return x0 + (deg + 90.0) / 180.0 * w; };
      auto Y = [&](double v) { return y0 + h - std::min(v, 1.05 * ymax) / (1.05 * ymax) * h; };
      svg += "<rect x=\"" + fmt("%.1f", x0) + "\" y=\"" + fmt("%.1f", y0) + "\" width=\"" + fmt("%.1f", w) +
             "\" height=\"" + fmt("%.1f", h) + "\" fill=\"none\" stroke=\"#999\"/>\n";
      const double bw = th.size() > 1 ? std::abs(X(th[1]) - X(th[0])) : w;
      for (std::size_t n = 0; n < th.size(); ++n)
        if (sim[n] > 0)
          svg += "<rect x=\"" + fmt("%.2f", X(th[n]) - 0.5 * bw) + "\" y=\"" + fmt("%.2f", Y(sim[n])) + "\" width=\"" +
                 fmt("%.2f", bw) + "\" height=\"" + fmt("%.2f", y0 + h - Y(sim[n])) + "\" fill=\"#8fd18f\"/>\n";
      auto line = [&](const std::vector<double>& v, const std::string& style) {
        std::string d;
        for (std::size_t n = 0; n < th.size(); ++n)
          d += (d.empty() ? "M" : " L") + fmt("%.1f", X(th[n])) + "," + fmt("%.1f", Y(v[n]));
        svg += "<path d=\"" + d + "\" fill=\"none\" " + style + "/>\n";
      };
      if (pl.contains("model_by_k")) {
        const auto& mk = pl.at("model_by_k");
        for (std::size_t k = 0; k < mk.size() && k < 4; ++k)
          line(mk[k].get<std::vector<double>>(),
               std::string("stroke=\"") + k_colors[k] + "\" stroke-width=\"1\" stroke-dasharray=\"4 2\"");
      }
      line(ct, "stroke=\"black\" stroke-width=\"1\" stroke-dasharray=\"1 2\"");
      line(model, "stroke=\"#d62728\" stroke-width=\"1.5\"");
      const bool pass = p.c->value("pass", false);
      svg += "<text x=\"" + fmt("%.1f", x0 + 4) + "\" y=\"" + fmt("%.1f", y0 + 12) + "\">alpha " +
             fmt("%.2g", p.alpha) + ", theta_i " + fmt("%.0f", p.theta_i) + "</text>\n";
      svg += "<text x=\"" + fmt("%.1f", x0 + 4) + "\" y=\"" + fmt("%.1f", y0 + h + 14) + "\" fill=\"" +
             (pass ? "#555" : "#d62728") + "\">L1 " + fmt("%.4f", p.c->value("l1", 0.0)) + " (thr " +
             fmt("%.4f", p.c->value("l1_threshold", 0.0)) + "), " + fmt("%.2g", p.c->value("rays", 0.0)) + " rays, " +
             fmt("%.2f", p.c->value("sim_wall_s", 0.0) + p.c->value("model_wall_s", 0.0)) + " s</text>\n";
    }
    svg += "</svg>\n";
    out.emplace_back(key, std::move(svg));
  }
  return out;
}

}  // namespace vgroove::validation
