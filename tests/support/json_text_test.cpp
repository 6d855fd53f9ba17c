// The JSON text every command writes (support/json_text.h): a number that is not finite is the
// string "nan", "inf" or "-inf" wherever it sits; everything else is nlohmann::json's text.
#include "vgroove/support/json_text.h"

#include <gtest/gtest.h>

#include <limits>

namespace vgroove::support {
namespace {

TEST(JsonText, NonFiniteNumbersAreStringsWhereverTheySit) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  nlohmann::json j = {{"a", inf}, {"b", {1.5, -inf, nan}}, {"c", {{"d", nan}, {"e", "inf"}}}, {"f", 0.1}, {"g", 3}};
  // nlohmann::json writes null for all three, which says neither which it was nor reads back.
  EXPECT_EQ(j.dump(), R"({"a":null,"b":[1.5,null,null],"c":{"d":null,"e":"inf"},"f":0.1,"g":3})");
  EXPECT_EQ(json_text(j), R"({"a":"inf","b":[1.5,"-inf","nan"],"c":{"d":"nan","e":"inf"},"f":0.1,"g":3})");
  EXPECT_EQ(json_text(j, 1), with_non_finite_as_text(j).dump(1));
  // Finite doubles keep their shortest round-trip text; a tree without a non-finite number is dumped as it is.
  const nlohmann::json k = {{"x", 0.1 + 0.2}, {"y", 1e-320}, {"z", -0.0}};
  EXPECT_EQ(json_text(k), k.dump());
  EXPECT_EQ(nlohmann::json::parse(json_text(k))["x"].get<double>(), 0.1 + 0.2);
  EXPECT_STREQ(non_finite_text(-inf), "-inf");
}

}  // namespace
}  // namespace vgroove::support
