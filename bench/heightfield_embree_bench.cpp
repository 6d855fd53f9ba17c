// vgroove bench: the exact heightfield tracer (sim/heightfield_tracer.h, double precision) beside
// Embree 3 (single precision) on the same triangles and the same rays, one core each.
//
// The field: Gaussian, Beckmann alpha 0.5, correlation length 8 cells, n x n cells (Arg), seed 1;
// the light at theta_i 60 deg, phi_i pi. One iteration traces one chunk of
// sim::kHeightfieldRaysPerChunk rays (the chunk's origins and directions) with each tracer.
//
// The Embree tracer is what a single-precision renderer does: the field's one period as a
// triangle mesh (the same two triangles per cell, vertices in float), a device with one thread
// (rays per second per core), rtcIntersect1 per tile crossed (the ray clipped to the period's box
// and moved by a whole period when it leaves it), after a hit the ray restarted at the float hit
// point with tnear = 1e-4 cells (the usual self-intersection offset), the reflection in float off
// the geometric normal. Escaped above the field's max height; lost when below its min, when it
// crosses more than 2^20 periods, or a NaN.
//
// Counters: rays_per_s and bounces_per_s (per core), and on the Embree side the fractions of a
// fixed sample of 16 chunks whose bounce count (k_changed) or exit bin (90 theta x 72 phi bins;
// bin_changed) differ from the exact tracer's, and lost (lost_embree). Run:
//   ./build/vgroove_heightfield_bench --benchmark_filter='/2048' (building the 2048^2 field and its
//   BVH takes ~20 s and ~1.3 GB).
#include "vgroove/sim/heightfield_tracer.h"
#include "vgroove/sim/rng.h"

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <numbers>
#include <vector>

namespace {

using namespace vgroove;
using V3 = Eigen::Vector3d;

constexpr double kThetaI = 60.0 * std::numbers::pi / 180.0;
constexpr int kThetaBins = 90, kPhiBins = 72;

struct EmbreeField {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  int n = 0;
  float zmin = 0.0f, zmax = 0.0f;
  EmbreeField() = default;
  EmbreeField(const EmbreeField&) = delete;
  EmbreeField& operator=(const EmbreeField&) = delete;
  ~EmbreeField() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

struct Fixture {
  sim::HeightfieldSurface surface;
  EmbreeField embree;
};

void build_embree(const sim::Heightfield& f, EmbreeField& e) {
  const int n = f.n;
  e.n = n;
  e.device = rtcNewDevice("threads=1");
  e.scene = rtcNewScene(e.device);
  RTCGeometry g = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const auto nv = static_cast<std::size_t>(n + 1) * (n + 1);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
  e.zmin = e.zmax = static_cast<float>(f.height(0, 0));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      float* p = v + 3 * (static_cast<std::size_t>(j) * (n + 1) + i);
      p[0] = static_cast<float>(i);
      p[1] = static_cast<float>(j);
      p[2] = static_cast<float>(f.height(i, j));
      e.zmin = std::min(e.zmin, p[2]);
      e.zmax = std::max(e.zmax, p[2]);
    }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), 2 * static_cast<std::size_t>(n) * n));
  const auto vid = [n](int i, int j) { return static_cast<unsigned>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      unsigned* t = idx + 6 * (static_cast<std::size_t>(j) * n + i);
      // lower (i, j), (i+1, j), (i+1, j+1); upper (i, j), (i+1, j+1), (i, j+1) (sim/heightfield.h)
      t[0] = vid(i, j), t[1] = vid(i + 1, j), t[2] = vid(i + 1, j + 1);
      t[3] = vid(i, j), t[4] = vid(i + 1, j + 1), t[5] = vid(i, j + 1);
    }
  rtcCommitGeometry(g);
  rtcAttachGeometry(e.scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(e.scene);
}

Fixture& fixture(int n) {
  static std::map<int, std::unique_ptr<Fixture>> cache;
  auto& f = cache[n];
  if (!f) {
    f = std::make_unique<Fixture>();
    f->surface = sim::make_heightfield_surface(sim::make_gaussian_heightfield({n, 0.5, 0.5, 8.0, 1}));
    build_embree(f->surface.field, f->embree);
  }
  return *f;
}

struct SimpleResult {
  bool escaped = false;
  int bounces = 0;
  V3 o = V3::Zero();
};

// One ray through the Embree scene, float throughout (header).
SimpleResult trace_embree(const EmbreeField& e, const V3& org0, const V3& dir0, int max_bounces = 1000) {
  SimpleResult r;
  const float nf = static_cast<float>(e.n);
  float o[3] = {static_cast<float>(org0.x()), static_cast<float>(org0.y()), static_cast<float>(org0.z())};
  float d[3] = {static_cast<float>(dir0.x()), static_cast<float>(dir0.y()), static_cast<float>(dir0.z())};
  float tnear = 0.0f;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (int a = 0; a < 2; ++a) {  // into the first period
    const float k = std::floor(o[a] / nf);
    o[a] -= k * nf;
  }
  for (int periods = 0; periods < (1 << 20);) {
    // Where the ray leaves the period's box [0, n]^2.
    float t_exit = INFINITY;
    int axis = -1;
    for (int a = 0; a < 2; ++a) {
      if (d[a] == 0.0f) continue;
      const float t = ((d[a] > 0.0f ? nf : 0.0f) - o[a]) / d[a];
      if (t < t_exit) t_exit = t, axis = a;
    }
    RTCRayHit rh{};
    rh.ray.org_x = o[0], rh.ray.org_y = o[1], rh.ray.org_z = o[2];
    rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
    rh.ray.tnear = tnear;
    rh.ray.tfar = t_exit;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(e.scene, &ctx, &rh);
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      if (++r.bounces > max_bounces) return r;
      const float t = rh.ray.tfar;
      for (int a = 0; a < 3; ++a) o[a] += t * d[a];
      const float ng[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
      const float dn = d[0] * ng[0] + d[1] * ng[1] + d[2] * ng[2];
      const float nn = ng[0] * ng[0] + ng[1] * ng[1] + ng[2] * ng[2];
      for (int a = 0; a < 3; ++a) d[a] -= 2.0f * dn / nn * ng[a];
      tnear = 1e-4f;
      continue;
    }
    if (!(d[0] == d[0]) || !(d[2] == d[2])) return r;  // NaN: lost
    const float z_exit = o[2] + t_exit * d[2];
    if (d[2] > 0.0f && (axis < 0 || z_exit > e.zmax)) {
      r.escaped = true;
      r.o = V3(d[0], d[1], d[2]).normalized();
      return r;
    }
    if (axis < 0 || (d[2] < 0.0f && z_exit < e.zmin)) return r;  // went through the surface: lost
    for (int a = 0; a < 3; ++a) o[a] += t_exit * d[a];
    o[axis] = d[axis] > 0.0f ? 0.0f : nf;  // the same point in the next period
    tnear = 0.0f;
    ++periods;
  }
  return r;
}

int bin_of(const V3& o) {
  const double tw = 0.5 * std::numbers::pi / kThetaBins, pw = 2.0 * std::numbers::pi / kPhiBins;
  const V3 u = o.normalized();
  const int t = std::clamp(static_cast<int>(std::floor(std::acos(std::min(1.0, u.z())) / tw)), 0, kThetaBins - 1);
  int p = static_cast<int>(std::floor(std::atan2(u.y(), u.x()) / pw + 0.5)) % kPhiBins;  // light at phi = pi
  if (p < 0) p += kPhiBins;
  return t * kPhiBins + p;
}

// The rays of chunk c, as trace_heightfield_chunk draws them.
void chunk_rays(const sim::HeightfieldSurface& s, std::int64_t c, std::vector<V3>& org, V3& dir) {
  sim::Rng rng(0, sim::kHeightfieldRayStream, static_cast<std::uint64_t>(c));
  const double nd = s.field.n, z0 = s.hierarchy.root().hi + 1.0;
  org.resize(static_cast<std::size_t>(sim::kHeightfieldRaysPerChunk));
  for (auto& p : org) {
    const double x = nd * rng.uniform(), y = nd * rng.uniform();
    p = V3(x, y, z0);
  }
  dir = -V3(std::sin(kThetaI) * std::cos(std::numbers::pi), std::sin(kThetaI) * std::sin(std::numbers::pi),
            std::cos(kThetaI));
}

void BM_heightfield_exact(benchmark::State& state) {
  Fixture& f = fixture(static_cast<int>(state.range(0)));
  std::vector<V3> org;
  V3 dir;
  std::int64_t rays = 0, bounces = 0, c = 0;
  for (auto _ : state) {
    chunk_rays(f.surface, c++ % 64, org, dir);
    for (const V3& p : org) {
      const sim::HeightfieldRayResult r = sim::trace_heightfield_ray(f.surface, p, dir);
      bounces += r.bounces;
      benchmark::DoNotOptimize(r.o);
    }
    rays += static_cast<std::int64_t>(org.size());
  }
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["bounces_per_s"] = benchmark::Counter(static_cast<double>(bounces), benchmark::Counter::kIsRate);
}

void BM_heightfield_embree(benchmark::State& state) {
  Fixture& f = fixture(static_cast<int>(state.range(0)));
  // The comparison, once, outside the timing: 16 chunks through both tracers.
  std::vector<V3> org;
  V3 dir;
  std::int64_t sample = 0, k_changed = 0, bin_changed = 0, lost = 0, exact_lost = 0;
  for (std::int64_t c = 0; c < 16; ++c) {
    chunk_rays(f.surface, c, org, dir);
    for (const V3& p : org) {
      const sim::HeightfieldRayResult a = sim::trace_heightfield_ray(f.surface, p, dir);
      const SimpleResult b = trace_embree(f.embree, p, dir);
      ++sample;
      exact_lost += a.how != sim::HeightfieldFate::escaped;
      if (!b.escaped) {
        ++lost;
        ++k_changed;
        ++bin_changed;
        continue;
      }
      k_changed += a.bounces != b.bounces;
      bin_changed += bin_of(a.o) != bin_of(b.o);
    }
  }
  std::int64_t rays = 0, bounces = 0, c = 0;
  for (auto _ : state) {
    chunk_rays(f.surface, c++ % 64, org, dir);
    for (const V3& p : org) {
      const SimpleResult r = trace_embree(f.embree, p, dir);
      bounces += r.bounces;
      benchmark::DoNotOptimize(r.o);
    }
    rays += static_cast<std::int64_t>(org.size());
  }
  const double s = static_cast<double>(sample);
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["bounces_per_s"] = benchmark::Counter(static_cast<double>(bounces), benchmark::Counter::kIsRate);
  state.counters["k_changed"] = static_cast<double>(k_changed) / s;
  state.counters["bin_changed"] = static_cast<double>(bin_changed) / s;
  state.counters["lost_embree"] = static_cast<double>(lost) / s;
  state.counters["lost_exact"] = static_cast<double>(exact_lost) / s;
}

// Exact first, Embree second, per size: the two rates side by side in one run.
BENCHMARK(BM_heightfield_exact)->Arg(256)->Arg(2048)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_heightfield_embree)->Arg(256)->Arg(2048)->Unit(benchmark::kMillisecond);

}  // namespace
