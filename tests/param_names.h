// Readable names for parameterized tests: (theta_v, theta_i) in degrees as "v7p3_im45p25".
#pragma once

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <tuple>

namespace vgroove::test_names {

using AnglePair = std::tuple<double, double>;  // (theta_v_deg, theta_i_deg)

// A number as test-name text: '.' -> 'p', '-' -> 'm'.
inline std::string name_text(double d) {
  std::ostringstream os;
  os << d;
  std::string s = os.str();
  for (char& c : s) c = c == '.' ? 'p' : c == '-' ? 'm' : c;
  return s;
}

inline std::string pair_name(const testing::TestParamInfo<AnglePair>& info) {
  return "v" + name_text(std::get<0>(info.param)) + "_i" + name_text(std::get<1>(info.param));
}

}  // namespace vgroove::test_names
