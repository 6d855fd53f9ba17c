// Tests of `vgroove energy --export` and `--audit` (app/cmd_energy_tables.cpp, app/energy_images.h,
// validation/energy_export.h):
// - the image encoders round-trip: a 16-bit PNG's samples within half a quantum, its text chunk; an
//   OpenEXR file's float channels exactly and its "vgroove" attribute;
// - an export's files hold the same tables and the metadata (layout, parametrization, quadrature,
//   version) in every one; its physics: E_ss + E_ms(F0 = 1) = 1 (the white furnace) for the V-groove
//   model within E_ss's bound + 1e-8, and for the Smith walk within 5 standard errors of the exact 1 - E_ss, the
//   compensation factor is (E_F + E_ms) / E_F;
// - bad input: one line naming the flag, exit 2, no file left (not even one of several);
// - --audit refuses --shard and runs a small grid to its table;
// - --eta (glass tables): bad input named, no file; a small run's JSON holds the arrays, its
//   averages and the reciprocity pairs.
#include "tests/cli_run.h"
#include "vgroove/app/energy_images.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

namespace vgroove::app {
namespace {

using testing_files::CliRun;
using testing_files::lines;
using testing_files::quoted;
using testing_files::read_text;
using testing_files::TempDir;
using testing_files::vgroove;
namespace fs = std::filesystem;

TEST(EnergyImages, Png16RoundTripsItsSamplesAndText) {
  std::vector<double> v;
  for (int k = 0; k < 3 * 5; ++k) v.push_back(k / 14.0);
  v[3] = 1.7;  // clamped to 1
  const std::string bytes = png16_bytes(v, 3, 5, 1.0, "{\"meta\": 1}");
  int rows = 0, cols = 0;
  std::string text;
  const std::vector<double> back = png16_values(bytes, rows, cols, text);
  EXPECT_EQ(rows, 3);
  EXPECT_EQ(cols, 5);
  EXPECT_EQ(text, "{\"meta\": 1}");
  for (std::size_t k = 0; k < v.size(); ++k) EXPECT_NEAR(back[k], std::min(v[k], 1.0), 0.5 / 65535 + 1e-15) << k;
  // A scale: values up to 4 in [0, 1] before quantizing.
  const std::vector<double> w = png16_values(png16_bytes({2.0, 4.0}, 1, 2, 4.0, ""), rows, cols, text);
  EXPECT_NEAR(w[0], 0.5, 0.5 / 65535);
  EXPECT_EQ(w[1], 1.0);
}

TEST(EnergyImages, ExrRoundTripsItsChannelsAndAttribute) {
  TempDir dir;
  const std::vector<double> a = {0.25, 0.5, 0.125, 1.0 / 3.0, 0.75, 0.875}, b = {1, 2, 3, 4, 5, 6};
  const std::string bytes = exr_bytes({{"E_ss", a}, {"dfg_bias", b}}, 2, 3, "{\"meta\": 2}");
  const std::string file = dir.file("t.exr");
  testing_files::write_text(file, bytes);
  Imf::InputFile in(file.c_str());
  const auto& dw = in.header().dataWindow();
  ASSERT_EQ(dw.max.x - dw.min.x + 1, 3);
  ASSERT_EQ(dw.max.y - dw.min.y + 1, 2);
  EXPECT_EQ(in.header().typedAttribute<Imf::StringAttribute>("vgroove").value(), "{\"meta\": 2}");
  std::vector<float> ra(6), rb(6);
  Imf::FrameBuffer fb;
  fb.insert("E_ss", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(ra.data()), sizeof(float), 3 * sizeof(float)));
  fb.insert("dfg_bias", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rb.data()), sizeof(float), 3 * sizeof(float)));
  in.setFrameBuffer(fb);
  in.readPixels(dw.min.y, dw.max.y);
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(ra[k], static_cast<float>(a[k])) << k;
    EXPECT_EQ(rb[k], static_cast<float>(b[k])) << k;
  }
}

nlohmann::json read_json(const std::string& f) { return nlohmann::json::parse(read_text(f)); }

std::vector<double> flat(const nlohmann::json& j) {
  std::vector<double> out;
  if (j.is_array()) {
    for (const auto& x : j) {
      const auto v = flat(x);
      out.insert(out.end(), v.begin(), v.end());
    }
  } else {
    out.push_back(j.get<double>());
  }
  return out;
}

TEST(EnergyExport, FilesHoldTheTablesMetadataAndTheWhiteFurnace) {
  TempDir dir;
  const std::string base = dir.file("ggx");
  const CliRun r = vgroove("energy --export " + quoted(base) +
                           " --size 4 --layout centres --ms-reference vgroove --ms-F0 0.04,1 --threads 2");
  ASSERT_EQ(r.status, 0) << r;
  const nlohmann::json j = read_json(base + ".json");
  for (const char* key : {"layout", "model", "quadrature", "multiple_scattering", "version", "git"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["layout"]["placement"], "texel centres: s = (i + 1/2) / n");
  EXPECT_EQ(j["model"]["masking"], "vcavity");  // the V-groove model's single scattering
  const std::vector<double> E = flat(j["values"]["E_ss"]), Ems = flat(j["values"]["E_ms"]),
                            comp = flat(j["values"]["compensation"]), scale = flat(j["values"]["dfg_scale"]),
                            bias = flat(j["values"]["dfg_bias"]);
  ASSERT_EQ(E.size(), 16u);
  ASSERT_EQ(Ems.size(), 32u);
  // F0 = 1, the white furnace: within E_ss's quadrature bound and the model's accuracy (1e-8).
  const double tol = j["quadrature"]["largest_bound"].get<double>() + 1e-8;
  for (std::size_t t = 0; t < 16; ++t) {
    EXPECT_NEAR(E[t] + Ems[16 + t], 1.0, tol) << "texel " << t;
    const double E_F = 0.04 * scale[t] + bias[t];
    EXPECT_NEAR(comp[t], (E_F + Ems[t]) / E_F, 1e-14);
    EXPECT_NEAR(scale[t] + bias[t], E[t], 1e-7);
  }
  // Every file carries the metadata.
  EXPECT_NE(read_text(base + ".h").find("\"layout\""), std::string::npos);
  int rows = 0, cols = 0;
  std::string text;
  const std::vector<double> png = png16_values(read_text(base + ".E_ss.png"), rows, cols, text);
  EXPECT_EQ(nlohmann::json::parse(text)["layout"], j["layout"]);
  for (std::size_t t = 0; t < 16; ++t) EXPECT_NEAR(png[t], E[t], 0.5 / 65535 + 1e-12);
  Imf::InputFile in((base + ".exr").c_str());
  EXPECT_EQ(nlohmann::json::parse(in.header().typedAttribute<Imf::StringAttribute>("vgroove").value())["quadrature"],
            j["quadrature"]);
  EXPECT_NE(read_text(base + ".npz").find("metadata.json"), std::string::npos);
}

TEST(EnergyExport, SmithWalkMultipleScatteringIsOneMinusTheExactSingleScattering) {
  TempDir dir;
  const std::string base = dir.file("w");
  const long paths = 20000;
  const CliRun r = vgroove("energy --export " + quoted(base) + " --size 3 --ms-reference smith_walk --ms-F0 1 --rays " +
                           std::to_string(paths) + " --formats json");
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_FALSE(fs::exists(base + ".npz"));
  const nlohmann::json j = read_json(base + ".json");
  EXPECT_EQ(j["model"]["masking"], "smith_height_correlated");
  const std::vector<double> E = flat(j["values"]["E_ss"]), Ems = flat(j["values"]["E_ms"]);
  for (std::size_t t = 0; t < E.size(); ++t) {
    const double p = 1.0 - E[t], se = std::sqrt(p * (1.0 - p) / paths) + 1.0 / paths;
    EXPECT_NEAR(Ems[t], p, 5.0 * se) << "texel " << t;
  }
}

TEST(EnergyExport, BadInputNamesTheFlagAndLeavesNoFile) {
  TempDir dir;
  const std::string base = dir.file("bad");
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {"--layout square", "--layout = \"square\" is not one of \"cycles\", \"centres\""},
      {"--size 1", "--size"},
      {"--ms-reference heightfield", "--ms-reference = \"heightfield\" is not one of"},
      {"--ms-reference vgroove --ms-F0 1.5", "--ms-F0 = 1.5 is out of range [0, 1]"},
      {"--ndf phong", "--ndf = phong"},
      {"--ndf ggx,beckmann", "--ndf has 2 values"},
      {"--formats json,tiff", "--formats = \"tiff\" is not one of"},
      {"--masking cook", "--masking = \"cook\" is not one of"},
      {"--audit", "--audit and --export are two runs"},
  };
  for (const Case& c : cases) {
    const CliRun r = vgroove("energy --export " + quoted(base) + " --size 4 " + c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r;
    EXPECT_EQ(lines(r.err), 1) << r;
    EXPECT_TRUE(fs::is_empty(dir.path())) << c.args;
  }
  // One target existing: refused before any work, and nothing else written.
  testing_files::write_text(base + ".h", "// mine\n");
  const CliRun r = vgroove("energy --export " + quoted(base) + " --size 4");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_NE(r.err.find("bad.h"), std::string::npos) << r;
  EXPECT_FALSE(fs::exists(base + ".json"));
  EXPECT_EQ(read_text(base + ".h"), "// mine\n");
}

TEST(EnergyAuditCli, RefusesShardsAndRunsASmallGrid) {
  const CliRun s = vgroove("energy --audit --shard 1/2 --out x.json");
  EXPECT_EQ(s.status, 2) << s;
  EXPECT_NE(s.err.find("vgroove validate SUITE --shard"), std::string::npos) << s;
  const CliRun p = vgroove("energy --audit --ndf phong");
  EXPECT_EQ(p.status, 2) << p;
  EXPECT_NE(p.err.find("--ndf = \"phong\""), std::string::npos) << p;
  TempDir dir;
  const std::string out = dir.file("audit.json");
  const CliRun r =
      vgroove("energy --audit --ndf ggx --alpha 0.6 --mu 0.3,0.9 --rays 4000 --max-k 3 --out " + quoted(out));
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_NE(r.out.find("against smith_walk"), std::string::npos) << r;
  const nlohmann::json j = read_json(out);
  EXPECT_EQ(j["spec"]["kind"], "energy_audit");
  EXPECT_TRUE(j["pass"].get<bool>());
  EXPECT_TRUE(j["summary"].contains("kulla_conty"));
}

// `energy --lobe-shape`: one line naming the flag for each bad input (exit 2, no file), and a small
// run whose controls pass, with the rows in its report: the Kulla-Conty lobe keeps the white
// furnace (model albedo 1) while f_ss alone does not.
TEST(EnergyLobeShapeCli, BadInputNamesTheFlagAndASmallRunReports) {
  TempDir dir;
  const std::string out = dir.file("lobes.json");
  for (const auto& [args, says] :
       std::vector<std::pair<std::string, std::string>>{{"--ndf phong", "--ndf: --lobe-shape takes one of"},
                                                        {"--alpha 0.005", "--alpha = 0.005 is out of range [0.01, 2]"},
                                                        {"--mu 0", "--mu = 0 is out of range"},
                                                        {"--audit", "--audit and --lobe-shape are two runs: give one"},
                                                        {"--dim flatland", "--dim: --lobe-shape is 3D"},
                                                        {"--shard 1/2", "--lobe-shape runs in one process"}}) {
    const CliRun r = vgroove("energy --lobe-shape " + args + " --out " + quoted(out));
    EXPECT_EQ(r.status, 2) << r;
    EXPECT_NE(r.err.find(says), std::string::npos) << r;
    EXPECT_EQ(lines(r.err), 1) << r;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
  const CliRun r = vgroove("energy --lobe-shape --alpha 0.5 --mu 0.5 --rays 20000 --threads 2 --out " + quoted(out));
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_NE(r.out.find("controls (vgroove_model on its surface, single on each k = 1 lobe): within noise"),
            std::string::npos)
      << r;
  const nlohmann::json j = read_json(out);
  EXPECT_EQ(j["kind"], "energy_lobe_shape");
  EXPECT_TRUE(j["controls_pass"].get<bool>());
  ASSERT_EQ(j["rows"].size(), 9u);  // 3 lobes x 2 references, 2 k = 1 controls, the V-groove model
  for (const nlohmann::json& row : j["rows"]) {
    EXPECT_NEAR(row["theta_i_deg"].get<double>(), 60.0, 1e-12);
    if (row["lobe"] == "kulla_conty") {
      EXPECT_NEAR(row["albedo_model"].get<double>(), 1.0, 1e-3) << row;
    }
    if (row["lobe"] == "single" && row["reference"] == "smith_walk") {
      EXPECT_LT(row["albedo_model"].get<double>(), 0.9);
    }
  }
}

TEST(EnergyGlassCli, BadInputNamesTheFlagAndASmallRunWritesItsTable) {
  TempDir dir;
  const std::string out = dir.file("glass.json");
  for (const auto& [args, says] : std::vector<std::pair<std::string, std::string>>{
           {"--eta 0", "--eta = 0 is out of range [0.1, 10]"},
           {"--eta 1", "--eta = 1 is no interface"},
           {"--eta nan", "--eta"},
           {"--eta 1.5 --ndf phong", "--ndf = \"phong\" is not one of \"ggx\", \"beckmann\" with --eta"},
           {"--eta 1.5 --side inside", "--side = \"inside\" is not one of \"above\", \"below\""},
           {"--eta 1.5 --grooves 0", "--grooves"},
           {"--eta 1.5 --audit", "--audit and --eta are two runs: give one"},
           {"--eta 1.5 --shard 3/2", "--shard = 3/2 is out of range: I/N with 1 <= I <= N"},
           {"--eta 1.5 --npy", "--npy applies to the conductor tables"},
           {"--side below", "--side applies to the glass tables (--eta)"},
           {"--eta 1.5 --mu 0", "--mu = 0 is out of range"}}) {
    const CliRun r = vgroove("energy " + args + " --alpha 0.5 --out " + quoted(out));
    EXPECT_EQ(r.status, 2) << args << "\n" << r;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << "\n" << r;
    EXPECT_EQ(lines(r.err), 1) << r;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
  const CliRun r = vgroove(
      "energy --eta 1.5 --dim 3d,flatland --alpha 0.3 --mu 1,0.5 --rays 5000 --grooves 500 --out " + quoted(out));
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_NE(r.out.find("reciprocity ggx 3d eta 1.5 alpha 0.3"), std::string::npos) << r;
  const nlohmann::json j = read_json(out);
  EXPECT_EQ(j["kind"], "glass_energy");
  EXPECT_EQ(j["arrays"]["E_R"]["shape"], (std::vector<int>{1, 2, 2, 1, 1, 2}));
  EXPECT_EQ(j["arrays"]["E_T_by_k"]["shape"], (std::vector<int>{1, 2, 2, 1, 1, 2, 17}));
  EXPECT_EQ(j["averages"]["cells"].size(), 4u);
  EXPECT_EQ(j["reciprocity"]["pairs"].size(), 2u);
  // E_R + E_T + bounce limit + vertex = 1 in every cell.
  for (std::size_t c = 0; c < 8; ++c)
    EXPECT_NEAR(j["arrays"]["E_R"]["values"][c].get<double>() + j["arrays"]["E_T"]["values"][c].get<double>() +
                    j["arrays"]["bounce_limit"]["values"][c].get<double>() +
                    j["arrays"]["vertex"]["values"][c].get<double>(),
                1.0, 1e-12);
}

}  // namespace
}  // namespace vgroove::app
