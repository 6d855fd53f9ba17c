#include "vgroove/analytic/detail/sin_batch.h"

#include "vgroove/common/simd.h"

namespace vgroove::analytic {

// Four angles per instruction in the AVX2 copy (common/simd.h).
VGROOVE_TARGET_CLONES
void sin_batch(const double* x, double* y, int n) {
  for (int m = 0; m < n; ++m) y[m] = sin_full(x[m]);
}

}  // namespace vgroove::analytic
