#include "vgroove/analytic/sin_batch.h"

namespace vgroove::analytic {

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
// One copy for AVX2 (four angles per instruction) and one for any x86-64, picked when the program
// starts. AVX2 without FMA: no product is fused, so both copies round alike.
[[gnu::target_clones("avx2", "default")]]
#endif
void sin_batch(const double* x, double* y, int n) {
  for (int m = 0; m < n; ++m) y[m] = sin_full(x[m]);
}

}  // namespace vgroove::analytic
