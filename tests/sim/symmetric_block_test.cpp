// Tests of sim/symmetric_block.h: the procedural surfaces' batch trace against sim::trace, ray by
// ray and tally by tally.
#include "vgroove/sim/symmetric_block.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <utility>

namespace vgroove::sim {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same(const TraceResult& a, const TraceResult& b, const char* what, int n) {
  EXPECT_EQ(a.how, b.how) << what << " " << n;
  EXPECT_EQ(a.bounces, b.bounces) << what << " " << n;
  if (a.bounces > 0) {
    EXPECT_EQ(a.first, b.first) << what << " " << n;
  }
  if (a.how == Termination::escaped) {
    EXPECT_TRUE(same_bits(a.exit_dir.x(), b.exit_dir.x()) && same_bits(a.exit_dir.y(), b.exit_dir.y()))
        << what << " " << n;
  }
}

// The 24-byte form rebuilds make_symmetric_groove's groove bit for bit (all trace() reads).
TEST(SymmetricBlock, GrooveDataRebuildsTheGroove) {
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int n = 0; n < 20000; ++n) {
    const double theta_v = n % 4 == 0 ? std::pow(10.0, -8.0 * U(g)) : std::numbers::pi * U(g);
    if (!(theta_v > 0.0)) continue;
    const Groove a = make_symmetric_groove(theta_v), b = symmetric_groove_from(symmetric_groove_data(a));
    for (int f = 0; f < 2; ++f) {
      const Facet &x = a.facet[f], &y = b.facet[f];
      ASSERT_TRUE(same_bits(x.edge.x(), y.edge.x()) && same_bits(x.edge.y(), y.edge.y())) << theta_v;
      ASSERT_TRUE(same_bits(x.normal.x(), y.normal.x()) && same_bits(x.normal.y(), y.normal.y())) << theta_v;
      ASSERT_TRUE(same_bits(x.r_xx, y.r_xx) && same_bits(x.r_xy, y.r_xy) && same_bits(x.r_yy, y.r_yy)) << theta_v;
      ASSERT_TRUE(same_bits(x.turn_to_other, y.turn_to_other) && same_bits(x.length, y.length)) << theta_v;
      ASSERT_TRUE(same_bits(a.rim_xs[f], b.rim_xs[f])) << theta_v;
    }
    ASSERT_TRUE(same_bits(a.rim_height, b.rim_height)) << theta_v;
  }
}

// Ray by ray against sim::trace: random grooves (apertures 1e-6 rad to pi), directions (to 1e-9
// of grazing) and landing points, rays exactly on the rims and the apex line and one ulp inside,
// bounce limits 1 to 3 and the default; the block's paths (settled at once or after further
// reflections, at the bounce limit, one by one, by sim::trace from the start) are all taken, and
// the first hit both ways (one facet excluded by the numerator's sign, or both tested). Blocks of
// 256 lanes and of fewer, not a multiple of the vector width; every round of next_reflections on
// the whole block, and block_reflections (rounds on the lanes still reflecting, gathered).
TEST(SymmetricBlock, EveryRayIsTracesBitForBit) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int paths[5] = {};
  long first_hit[2][2] = {};  // [both facets tested][left to sim::trace]
  for (int max_bounces : {1, 2, 3, 100000}) {
    const TraceOptions opt{max_bounces};
    for (int block = 0; block < 60; ++block) {
      SymmetricBlock in;
      const int n = block % 3 == 0 ? kSymmetricBlock - 1 - block % 7 : kSymmetricBlock;
      for (int q = 0; q < n; ++q) {
        const double u = U(g);
        // Narrow (more reflections than the rounds), nearly flat, 10 to 100 reflections, any.
        const double theta_v = u < 0.1 ? 1e-6 + 1e-3 * U(g)
                                       : (u < 0.2 ? std::numbers::pi * (1.0 - 1e-9 * U(g))
                                                  : (u < 0.3 ? 0.03 + 0.3 * U(g) : std::numbers::pi * U(g)));
        const SymmetricGrooveData d = symmetric_groove_data(make_symmetric_groove(std::max(theta_v, 1e-6)));
        in.left_x[q] = d.left_x, in.right_x[q] = d.right_x, in.rim_height[q] = d.rim_height;
        const double t = (U(g) < 0.1 ? 1.0 - 1e-9 * U(g) : U(g)) * (U(g) < 0.5 ? -1.0 : 1.0) * 0.5 * std::numbers::pi;
        const Vec2 dir = beam_direction(t);
        in.dx[q] = dir.x(), in.dy[q] = dir.y();
        const double v = U(g);
        double x = d.left_x + U(g) * (d.right_x - d.left_x);
        if (v < 0.05)
          x = d.left_x;
        else if (v < 0.1)
          x = d.right_x;
        else if (v < 0.15)
          x = std::nextafter(d.left_x, 1.0);
        else if (v < 0.2)
          x = 0.0;
        in.x[q] = x;
      }
      // The block's reflections, every round taken (block_reflections stops early when few lanes
      // remain; TalliesEqualThePathBefore runs it as the surfaces do).
      SymmetricHits h, hb;
      first_reflections(in, n, h);
      for (int r = 0; r < kBlockRounds; ++r) next_reflections(in, n, max_bounces, h);
      block_reflections(in, n, max_bounces, kBlockRounds, hb);
      for (int q = 0; q < n; ++q) {
        ++paths[h.path[q]];
        const Groove gr = symmetric_groove_from({in.left_x[q], in.right_x[q], in.rim_height[q]});
        const TraceResult ref = trace(gr, Ray2{Vec2(in.x[q], in.rim_height[q]), Vec2(in.dx[q], in.dy[q])}, opt);
        expect_same(finish_lane(in, h, q, opt), ref, "lane", q);
        expect_same(finish_lane(in, hb, q, opt), ref, "block_reflections, lane", q);
        // The first hit: trace() tests both facets unless the numerator's sign excludes one.
        const double sn = in.x[q] * in.dy[q] - in.rim_height[q] * in.dx[q];
        const double den_l = in.left_x[q] * in.dy[q] - in.rim_height[q] * in.dx[q];
        const double den_r = in.right_x[q] * in.dy[q] - in.rim_height[q] * in.dx[q];
        ++first_hit[(sn * den_l < 0.0) == (sn * den_r < 0.0) ? 1 : 0][h.path[q] == 2 ? 1 : 0];
      }
    }
  }
  // Path 3 (a vertex met after a reflection) needs a rounded position exactly on a rim: rare, and
  // checked whenever it occurs.
  for (int p : {0, 1, 2, 4}) EXPECT_GT(paths[p], 0) << "path " << p << " never taken";
  // Both first-hit cases taken, and the block settles most rays of each itself.
  for (int both = 0; both < 2; ++both) {
    EXPECT_GT(first_hit[both][0], 4 * first_hit[both][1]) << (both ? "both facets tested" : "one facet");
  }
}

// Whole tallies: the batch trace against the path before it (one ray at a time with sim::trace,
// bins by atan2 and acos), flatland and 3D, three NDFs, smooth and rough, normal to grazing
// incidence: every count equal. The bins are found by comparisons instead of atan2/acos; the two
// can differ only for an exit within rounding of a bin edge (~1e-15 per ray), so equal tallies
// are the test (and the sampled distributions are the same, ray for ray).
TEST(SymmetricBlock, TalliesEqualThePathBefore) {
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann, NdfKind::phong}) {
    for (double alpha : {0.1, 1.0}) {
      for (double ti : {0.0, 45.0, 89.5}) {
        const double theta_i = ti * std::numbers::pi / 180.0;
        const Microsurface m = make_microsurface({ndf, alpha, 3000, 7});
        MicrosurfaceTraceOptions o;
        o.theta_i = theta_i, o.rays = 40000, o.seed = 9, o.theta_o_bins = 90, o.max_k = 8;
        for (Sampling s : {Sampling::random, Sampling::stratified}) {
          o.sampling = s;
          for (std::int64_t c = 0; c < chunk_count(o); ++c) {
            const MicrosurfaceTally a = trace_microsurface_chunk(m, o, c),
                                    b = trace_microsurface_chunk_reference(m, o, c);
            ASSERT_EQ(a.theta_o_by_k, b.theta_o_by_k) << ndf_name(ndf) << " " << alpha << " " << ti;
            ASSERT_EQ(a.rays, b.rays);
            ASSERT_EQ(a.vertex_hits, b.vertex_hits);
            ASSERT_EQ(a.bounce_limit, b.bounce_limit);
            ASSERT_EQ(a.bounces, b.bounces);
          }
        }
        const Microsurface3d m3 = make_microsurface3d({ndf, std::min(alpha, 1.0), 3000, 7});
        Microsurface3dTraceOptions o3;
        o3.theta_i = std::min(theta_i, 1.5), o3.rays = 40000, o3.seed = 9, o3.theta_bins = 30, o3.phi_bins = 24;
        o3.max_k = 8;
        for (std::int64_t c = 0; c < chunk_count(o3); ++c) {
          const Microsurface3dTally a = trace_microsurface3d_chunk(m3, o3, c),
                                    b = trace_microsurface3d_chunk_reference(m3, o3, c);
          ASSERT_EQ(a.hist_by_k, b.hist_by_k) << ndf_name(ndf) << " " << alpha << " " << ti;
          ASSERT_EQ(a.rays, b.rays);
          ASSERT_EQ(a.vertex_hits, b.vertex_hits);
          ASSERT_EQ(a.bounces, b.bounces);
        }
      }
    }
  }
}

// Chunks added into one tally (as trace_microsurface and the suites sum them) equal the chunks'
// own tallies merged, for the batch trace and for a surface built without the batch data (the
// one-ray path), in flatland and 3D.
TEST(SymmetricBlock, ChunksAddedIntoOneTallyEqualTheMergedChunks) {
  Microsurface m = make_microsurface({NdfKind::ggx, 0.7, 2000, 5});
  MicrosurfaceTraceOptions o;
  o.theta_i = 0.4, o.rays = 3 * kRaysPerChunk + 1000, o.seed = 2, o.max_k = 6;
  Microsurface3d m3 = make_microsurface3d({NdfKind::beckmann, 0.7, 2000, 5});
  Microsurface3dTraceOptions o3;
  o3.theta_i = 0.9, o3.rays = 2 * kRaysPerChunk + 77, o3.seed = 2, o3.theta_bins = 20, o3.phi_bins = 16, o3.max_k = 6;
  for (bool batch : {true, false}) {
    if (!batch) m.data.clear(), m3.data.clear();
    MicrosurfaceTally into(o.theta_o_bins, o.max_k), merged(o.theta_o_bins, o.max_k);
    for (std::int64_t c = 0; c < chunk_count(o); ++c) {
      trace_microsurface_chunk(m, o, c, into);
      merged.merge(trace_microsurface_chunk(m, o, c));
    }
    EXPECT_EQ(into.theta_o_by_k, merged.theta_o_by_k) << batch;
    EXPECT_EQ(into.theta_o, merged.theta_o) << batch;
    EXPECT_EQ(into.by_k, merged.by_k) << batch;
    EXPECT_EQ(into.rays, o.rays) << batch;
    EXPECT_EQ(into.escaped, merged.escaped) << batch;
    EXPECT_EQ(into.bounces, merged.bounces) << batch;
    Microsurface3dTally into3(o3.theta_bins, o3.phi_bins, o3.max_k), merged3(o3.theta_bins, o3.phi_bins, o3.max_k);
    for (std::int64_t c = 0; c < chunk_count(o3); ++c) {
      trace_microsurface3d_chunk(m3, o3, c, into3);
      merged3.merge(trace_microsurface3d_chunk(m3, o3, c));
    }
    EXPECT_EQ(into3.hist_by_k, merged3.hist_by_k) << batch;
    EXPECT_EQ(into3.hist, merged3.hist) << batch;
    EXPECT_EQ(into3.rays, o3.rays) << batch;
    EXPECT_EQ(into3.escaped, merged3.escaped) << batch;
    EXPECT_EQ(into3.bounces, merged3.bounces) << batch;
  }
}

// The same at the suites' finest bins: 3D theta 10,000 over 90 deg (1.6e-4 rad wide), 3D phi
// 10,000 (6.3e-4 rad; each with the other coarse, to keep the tallies small) and flatland 100,000
// over 180 deg: where the bins are narrowest, the guesses lie nearest to edges and the edge tests
// decide most often.
TEST(SymmetricBlock, TalliesEqualThePathBeforeAtTheFinestBins) {
  for (double alpha : {0.3, 1.0}) {
    const Microsurface3d m3 = make_microsurface3d({NdfKind::ggx, alpha, 3000, 3});
    for (const auto& [tb, pb] : {std::pair{10000, 24}, std::pair{30, 10000}}) {
      Microsurface3dTraceOptions o3;
      o3.theta_i = 0.7, o3.rays = 40000, o3.seed = 4, o3.theta_bins = tb, o3.phi_bins = pb, o3.max_k = 0;
      for (std::int64_t c = 0; c < chunk_count(o3); ++c) {
        const Microsurface3dTally a = trace_microsurface3d_chunk(m3, o3, c),
                                  b = trace_microsurface3d_chunk_reference(m3, o3, c);
        ASSERT_EQ(a.hist_by_k, b.hist_by_k) << alpha << " " << tb << " x " << pb;
        ASSERT_EQ(a.rays, b.rays);
      }
    }
    const Microsurface m = make_microsurface({NdfKind::ggx, alpha, 3000, 3});
    MicrosurfaceTraceOptions o;
    o.theta_i = 0.7, o.rays = 40000, o.seed = 4, o.theta_o_bins = 100000, o.max_k = 2;
    for (std::int64_t c = 0; c < chunk_count(o); ++c) {
      const MicrosurfaceTally a = trace_microsurface_chunk(m, o, c), b = trace_microsurface_chunk_reference(m, o, c);
      ASSERT_EQ(a.theta_o_by_k, b.theta_o_by_k) << alpha;
      ASSERT_EQ(a.rays, b.rays);
    }
  }
}

}  // namespace
}  // namespace vgroove::sim
