// Tests of sim/profile_tally.h: the beam over a polyline profile, tallied.
//
// - The V-groove polyline of a procedural microsurface gives trace_microsurface's tally count for
//   count (the same landing points, each ray traced by the other tracer).
// - Random profiles: every ray leaves (F = 1: albedo 1), none lost, at normal and grazing
//   incidence, smooth and rough; chunks merged in any order give the same tally.
#include "vgroove/sim/profile_tally.h"
#include "vgroove/sim/random_profile.h"

#include <gtest/gtest.h>

#include <numbers>

namespace vgroove::sim {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

void expect_same(const MicrosurfaceTally& a, const MicrosurfaceTally& b, const std::string& where) {
  EXPECT_EQ(a.rays, b.rays) << where;
  EXPECT_EQ(a.escaped, b.escaped) << where;
  EXPECT_EQ(a.vertex_hits, b.vertex_hits) << where;
  EXPECT_EQ(a.bounce_limit, b.bounce_limit) << where;
  EXPECT_EQ(a.not_upward, b.not_upward) << where;
  EXPECT_EQ(a.bounces, b.bounces) << where;
  EXPECT_EQ(a.by_k, b.by_k) << where;
  EXPECT_EQ(a.theta_o_by_k, b.theta_o_by_k) << where;
}

TEST(ProfileTally, VGroovePolylineGivesTheMicrosurfaceTally) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.3, 1.0}) {
      MicrosurfaceOptions mo;
      mo.ndf = ndf, mo.alpha = alpha, mo.grooves = 5000, mo.seed = 3;
      const Microsurface m = make_microsurface(mo);
      const Polyline p = vgroove_polyline(m.theta_m);
      for (double theta_deg : {0.0, 40.0, 80.0})
        for (Sampling sampling : {Sampling::random, Sampling::stratified}) {
          MicrosurfaceTraceOptions to;
          to.theta_i = deg(theta_deg);
          to.rays = 40000;
          to.sampling = sampling;
          to.seed = 4;
          const std::string where = std::string(ndf_name(ndf)) + " alpha=" + std::to_string(alpha) +
                                    " theta_i=" + std::to_string(theta_deg) + " " + sampling_name(sampling);
          expect_same(trace_profile(p, to), trace_microsurface(m, to), where);
        }
    }
}

TEST(ProfileTally, RandomProfilesReflectEveryRay) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.01, 0.3, 1.0, 2.0}) {
      RandomProfileOptions po;
      po.ndf = ndf, po.alpha = alpha, po.segments = 1 << 13, po.seed = 8;
      const Polyline p = make_random_profile(po);
      for (double theta_deg : {0.0, 60.0, 89.9, 89.99}) {
        MicrosurfaceTraceOptions to;
        to.theta_i = deg(theta_deg);
        to.rays = 5000;
        to.seed = 2;
        const MicrosurfaceTally t = trace_profile(p, to);
        EXPECT_EQ(t.rays, 5000);
        EXPECT_EQ(t.escaped, 5000) << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << theta_deg
                                   << " vertex=" << t.vertex_hits << " limit=" << t.bounce_limit
                                   << " not_upward=" << t.not_upward;
        if (alpha >= 1.0 && theta_deg == 0.0) {
          EXPECT_GT(t.bounces, 5000 + 500);  // multiple scattering
        }
      }
    }
}

TEST(ProfileTally, ChunksMergeToTheSameTallyInAnyOrder) {
  RandomProfileOptions po;
  po.ndf = NdfKind::ggx, po.alpha = 0.8, po.segments = 1 << 12, po.seed = 1;
  const Polyline p = make_random_profile(po);
  MicrosurfaceTraceOptions to;
  to.theta_i = deg(30);
  to.rays = 3 * kRaysPerChunk + 17;
  const MicrosurfaceTally forward = trace_profile(p, to);
  MicrosurfaceTally backward(to.theta_o_bins, to.max_k);
  for (std::int64_t c = chunk_count(to) - 1; c >= 0; --c) backward.merge(trace_profile_chunk(p, to, c));
  expect_same(forward, backward, "reverse merge");
}

}  // namespace
}  // namespace vgroove::sim
