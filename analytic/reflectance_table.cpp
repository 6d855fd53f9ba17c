#include "vgroove/analytic/reflectance_table.h"

#include <cassert>

namespace vgroove::analytic {

ReflectanceTable::ReflectanceTable(const std::function<double(double)>& F, int n) : n_(n) {
  assert(n >= 3);
  f_.resize(static_cast<std::size_t>(n) + 1);
  for (int j = 0; j <= n; ++j) f_[static_cast<std::size_t>(j)] = F(static_cast<double>(j) / n);
}

}  // namespace vgroove::analytic
