// vgroove analytic: tables of E_ss(mu, alpha), E_avg(alpha) and the split-sum DFG terms
// (albedo_single.h) at any resolution, in each engine's layout: direction axis in mu or theta_i,
// roughness axis alpha or r with alpha = r^2, texels at the ends or the centres, clamp, memory
// order, float coordinates and saturation. cycles_ggx_E_layout() is Blender Cycles' table_ggx_E
// and table_ggx_Eavg layout, reproduced to the printed 1e-6 (data/reference/cycles_ggx_albedo.json).
// Tests: tests/analytic/albedo_table_test.cpp (AlbedoTable.CyclesGgxEIsReproducedToItsPrintedPrecision,
// AlbedoTable.CyclesGgxEavgIsReproduced, AlbedoTable.LayoutsPlaceTheTexels,
// AlbedoTable.DfgTableAddsToTheAlbedoTable, AlbedoTableLong.CyclesGgxEavgIsReproducedEverywhere).
// Layouts: docs/albedo_tables.md. Derivation: docs/derivations/albedo.md.
#pragma once

#include "vgroove/analytic/albedo_single.h"

#include <vector>

namespace vgroove::analytic {

enum class DirectionAxis : unsigned char { cos_theta, theta };
enum class RoughnessAxis : unsigned char { alpha, roughness_squared };
enum class TexelPlacement : unsigned char { endpoints, centers };
enum class FastAxis : unsigned char { roughness, direction };

struct TableLayout {
  int n_direction = 32;
  int n_roughness = 32;
  DirectionAxis direction = DirectionAxis::cos_theta;
  RoughnessAxis roughness = RoughnessAxis::roughness_squared;
  TexelPlacement placement = TexelPlacement::endpoints;
  FastAxis fast = FastAxis::roughness;
  double s_min = 1e-4;             // each axis coordinate s clamped to [s_min, 1]
  bool float_coordinates = false;  // s, alpha and mu rounded to float as a float generator has them
  bool saturate = false;           // values clamped to [0, 1]
};

// Blender Cycles' table_ggx_E: 32 x 32, [y][x] with y the mu index and x the roughness index,
// mu = clamp(y / 31, 1e-4, 1), r = clamp(x / 31, 1e-4, 1), alpha = r^2, in float, saturated.
TableLayout cycles_ggx_E_layout();

// The axis coordinate s of index i of n (clamped to [s_min, 1]), and what it stands for.
double layout_coordinate(const TableLayout& l, int i, int n);
double layout_mu(const TableLayout& l, int i);     // i: the direction index
double layout_alpha(const TableLayout& l, int j);  // j: the roughness index
// The flat index of (direction i, roughness j).
int layout_index(const TableLayout& l, int i, int j);

struct AlbedoTable {
  TableLayout layout;
  std::vector<double> values;  // layout_index order; E_avg tables: one per roughness index
  std::vector<double> errors;  // each value's bound
  double max_error = 0.0;
  bool converged = true;
  long evaluations = 0;
};

// E_ss at every (mu, alpha) of the layout.
AlbedoTable albedo_table(const MicrofacetModel& m, const TableLayout& l, const AlbedoOptions& opt = {});
// E_avg at every alpha of the layout (its direction axis unused).
AlbedoTable albedo_average_table(const MicrofacetModel& m, const TableLayout& l, const AlbedoOptions& opt = {});
// The split-sum scale and bias (Karis 2013) at every (mu, alpha): two tables of one layout.
struct SplitSumTable {
  AlbedoTable scale, bias;
};
SplitSumTable dfg_table(const MicrofacetModel& m, const TableLayout& l, const AlbedoOptions& opt = {});

}  // namespace vgroove::analytic
