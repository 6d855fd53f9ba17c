// Tests of `vgroove sample --model walter` (analytic/walter_sampling.h through the command line):
// the chi-square over both hemispheres accepts; the mean weight f |cos theta_o| / pdf equals the
// albedo R + T of Walter's BSDF integrated here by quadrature (analytic/hemisphere_quadrature.h),
// within 4.5 of its standard errors; the reflected share equals the pdf's integral over the upper
// hemisphere within 4.5 binomial sigmas; the same figures held to a wrong albedo (the V-cavity's
// G2) and a wrong share (flat Fresnel R at the light's angle) are told apart. Bad input: one line
// naming the flag and its range, exit 2, no result file; --help says the ranges enforced.
#include "vgroove/analytic/hemisphere_quadrature.h"
#include "vgroove/analytic/walter.h"
#include "vgroove/analytic/walter_sampling.h"
#include "vgroove/common/angles.h"
#include "vgroove/optics/fresnel.h"

#include "tests/cli_run.h"
#include "tests/test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/stat.h>
#include <cmath>
#include <numbers>
#include <string>

namespace vgroove::app {
namespace {

using nlohmann::json;
using testing_files::CliRun;
using testing_files::read_text;
using testing_files::TempDir;
using testing_files::vgroove;

struct Case {
  const char* ndf;
  double alpha, eta, theta_i_deg;
  const char* masking;
};

std::string flags(const Case& c) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "--model walter --ndf %s --alpha %.17g --eta %.17g --theta-i-deg %.17g --masking %s",
                c.ndf, c.alpha, c.eta, c.theta_i_deg, c.masking);
  return buf;
}

analytic::Dir3 light(const Case& c) { return analytic::dir3(deg_to_rad(c.theta_i_deg), std::numbers::pi); }

// Over the upper hemisphere (sign +1) or the lower one (-1, mirrored up), with the pole at the
// lobe's peak: the mirror direction, or Snell's (mirrored up; the normal under total internal
// reflection).
template <class F>
double over(const Case& c, int sign, F&& f) {
  const analytic::Dir3 i = light(c);
  const double st = std::sin(deg_to_rad(c.theta_i_deg)) / (sign > 0 ? 1.0 : c.eta);
  const analytic::Dir3 pole = st < 1.0 ? analytic::Dir3{st, 0.0, std::sqrt(1.0 - st * st)} : analytic::Dir3{0, 0, 1};
  analytic::HemisphereOptions opt;
  opt.tol = 1e-7;
  opt.scale = c.alpha;
  return analytic::integrate_hemisphere(
             pole,
             [&](const analytic::Dir3& o) {
               return f(i, analytic::Dir3{o.x, o.y, sign * o.z}) * o.z;
             },
             opt)
      .value;
}

// R + T of Walter's BSDF with the G2 `g`: the integral of f |cos theta_o| over the sphere.
double albedo(const Case& c, analytic::MaskingKind g) {
  const NdfKind ndf = *ndf_from_name(c.ndf);
  auto f = [&](const analytic::Dir3& i, const analytic::Dir3& o) {
    return analytic::walter_bsdf(i, o, ndf, c.alpha, c.eta, g);
  };
  return over(c, 1, f) + over(c, -1, f);
}

// The probability the sampler reflects: its pdf integrated over the upper hemisphere (divided by
// cos theta_o, which over() multiplies in).
double reflected_share(const Case& c) {
  const NdfKind ndf = *ndf_from_name(c.ndf);
  return over(c, 1, [&](const analytic::Dir3& i, const analytic::Dir3& o) {
    return analytic::walter_pdf(ndf, c.alpha, c.eta, i, o) / o.z;
  });
}

json run(const Case& c, long n, const TempDir& dir) {
  const std::string out = dir.file("walter.json");
  const CliRun r =
      vgroove("sample " + flags(c) + " --n " + std::to_string(n) + " --seed 3 --force --out '" + out + "'");
  EXPECT_EQ(r.status, 0) << r;
  EXPECT_CONTAINS(r.out, "accepted");
  return json::parse(read_text(out)).at("result");
}

// GGX (Smith VNDF proposal) from both sides and Beckmann and Phong (|m.n| D(m)), each G2.
const Case kCases[] = {
    {"ggx", 0.5, 1.5, 40, "smith"},
    {"ggx", 0.3, 1 / 1.5, 30, "smith_separable"},
    {"beckmann", 0.4, 2.4, 60, "smith"},
    {"phong", 0.6, 1 / 1.33, 20, "vcavity"},
};
constexpr long kDraws = 100000;

TEST(CmdSampleWalter, MeanWeightIsTheAlbedoAndTheReflectedShareThePdfs) {
  TempDir dir;
  for (const Case& c : kCases) {
    const json j = run(c, kDraws, dir);
    const double n = static_cast<double>(kDraws);
    const double mean = j.at("weight_mean").get<double>(), se = j.at("weight_standard_error").get<double>();
    const double want = albedo(c, *analytic::masking_from_flag(c.masking));
    EXPECT_NEAR(mean, want, 4.5 * se) << flags(c);
    EXPECT_NEAR(j.at("weight_mean_reflected").get<double>() + j.at("weight_mean_transmitted").get<double>(), mean,
                1e-12);
    const double p = reflected_share(c);
    const double share = j.at("reflected").get<double>() / n;
    EXPECT_NEAR(share, p, 4.5 * std::sqrt(p * (1.0 - p) / n)) << flags(c);
    EXPECT_NEAR(j.at("pdf_reflected").get<double>(), p, 1e-3) << flags(c);
    // Both sides carry draws; every draw is counted once.
    EXPECT_GT(j.at("transmitted").get<double>(), 0.1 * n) << flags(c);
    EXPECT_EQ(j.at("reflected").get<double>() + j.at("transmitted").get<double>() +
                  j.at("table").at("observed_no_direction").get<double>(),
              n);
    EXPECT_EQ(j.at("table").at("observed").size(), 16u);  // 2 x --cos-bins 8
  }
}

// The same figures held to wrong values are told apart (GGX, whose weights vary least): the albedo with the V-cavity's
// G2 in place of Smith's (Smith's two forms differ by 0.1-0.3 per cent here, below 4.5 standard errors of 10^5 draws),
// the reflected share as a flat interface's Fresnel R at the light's angle.
TEST(CmdSampleWalter, WrongAlbedoAndShareAreToldApart) {
  TempDir dir;
  for (const Case& c : {kCases[0], kCases[1]}) {
    const json j = run(c, kDraws, dir);
    const double mean = j.at("weight_mean").get<double>(), se = j.at("weight_standard_error").get<double>();
    const double wrong = albedo(c, analytic::MaskingKind::vcavity);
    EXPECT_GT(std::abs(mean - wrong), 4.5 * se) << flags(c) << ": mean " << mean << " wrong " << wrong;
    const double n = static_cast<double>(kDraws);
    const double flat = optics::fresnel_dielectric(std::cos(deg_to_rad(c.theta_i_deg)), c.eta);
    const double share = j.at("reflected").get<double>() / n;
    EXPECT_GT(std::abs(share - flat), 4.5 * std::sqrt(flat * (1.0 - flat) / n)) << flags(c);
  }
}

bool exists(const std::string& p) {
  struct stat s {};
  return ::stat(p.c_str(), &s) == 0;
}

TEST(CmdSampleWalter, BadInputIsOneLineNamingTheFlag) {
  TempDir dir;
  const std::string out = dir.file("never.json");
  const std::string tail = " --n 1000 --out '" + out + "'";
  const std::pair<std::string, std::string> cases[] = {
      {"--model walter --eta 0", "--eta = 0 is out of range (0, 1000], not 1"},
      {"--model walter --eta=-1.5", "--eta = -1.5 is out of range (0, 1000], not 1"},
      {"--model walter --eta 1", "--eta = 1 is out of range (0, 1000], not 1, with --model walter"},
      {"--model walter --eta nan", "--eta"},
      {"--model walter --eta 1001", "--eta = 1001 is out of range (0, 1000], not 1"},
      {"--model walter --masking bogus", "--masking = \"bogus\" is not one of \"smith\", \"smith_separable\""},
      {"--model walter --ndf phong", "--masking = \"smith_separable\" needs --ndf ggx or beckmann"},
      {"--model walter --strategy vndf", "--strategy applies to --model vgroove and vgroove-nonsymmetric only"},
      {"--model walter --max-k 3", "--max-k applies to --model vgroove and vgroove-nonsymmetric only"},
      {"--model walter --dim flatland", "--dim = \"flatland\" is not available with --model walter"},
      {"--eta 1.5", "--eta applies to --model walter and vgroove-dielectric only (--model = \"vgroove\")"},
      {"--model vgroove-nonsymmetric --masking smith", "--masking applies to --model walter only"},
      {"--model walter --alpha 0", "--alpha = 0 is out of range [0.01, 2]"},
      {"--model walter --theta-i-deg 90", "--theta-i-deg = 90 is out of range [0, 89.9]"},
      {"--model cook-torrance", "\"vgroove\", \"vgroove-nonsymmetric\", \"walter\""},
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = vgroove("sample " + args + tail);
    EXPECT_EQ(r.status, 2) << args << ": " << r;
    EXPECT_EQ(r.out, "") << args;
    EXPECT_EQ(testing_files::lines(r.err), 1) << args << ": " << r;
    EXPECT_CONTAINS(r.err, message);
    EXPECT_FALSE(exists(out)) << args;
  }
  // Too few draws for a chi-square test: refused after the draws, still without a file.
  const CliRun few = vgroove("sample --model walter --n 1 --out '" + out + "'");
  EXPECT_EQ(few.status, 2) << few;
  EXPECT_EQ(testing_files::lines(few.err), 1) << few;
  EXPECT_CONTAINS(few.err, "--n = 1 is too few samples for a chi-square test");
  EXPECT_FALSE(exists(out));
  // The control: the same flags with a good eta run and write the file.
  const CliRun ok = vgroove("sample --model walter --eta 1.0001" + tail);
  EXPECT_EQ(ok.status, 0) << ok;
  EXPECT_TRUE(exists(out));
}

TEST(CmdSampleWalter, HelpSaysWhatIsEnforced) {
  const CliRun r = vgroove("sample --help");
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_CONTAINS(r.out, "(0, 1000], not 1");
  EXPECT_CONTAINS(r.out, "vgroove-nonsymmetric (Eq. 23");
  EXPECT_CONTAINS(r.out, "or walter (Walter et al. 2007");
  EXPECT_CONTAINS(r.out, "walter: 3d only");
  EXPECT_CONTAINS(r.out, "not with walter");
  EXPECT_CONTAINS(r.out, "smith ones need ggx or beckmann");
}

}  // namespace
}  // namespace vgroove::app
