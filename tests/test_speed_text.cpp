// How speeds are printed (scene/speed_text.hpp): a speed below c never reads as c.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lightcone/scene/speed_text.hpp"

namespace lightcone {
namespace {

TEST(SpeedText, SixDigitsWhereTheyShowTheSpeedBelowC) {
  EXPECT_EQ(speed_text(0), "0");
  EXPECT_EQ(speed_text(0.5), "0.5");
  EXPECT_EQ(speed_text(std::sqrt(0.125)), "0.353553");
  EXPECT_EQ(speed_text(0.999997), "0.999997");
  EXPECT_EQ(speed_text(0.35355339, 4), "0.3536");
}

TEST(SpeedText, MoreDigitsWhereFewerWouldRoundUpToC) {
  // gamma 5202: 1 - beta = 1 / (2 gamma^2).
  const double beta = std::sqrt(1 - 1 / (5202.07 * 5202.07));
  EXPECT_EQ(speed_text(beta), "0.99999998");
  EXPECT_EQ(speed_text(0.99996, 4), "0.99996");
  // The double just below 1, 1 - 2^-53, needs 16.
  EXPECT_EQ(speed_text(std::nextafter(1.0, 0.0)), "0.9999999999999999");
  EXPECT_EQ(speed_text(1), "1");
}

}  // namespace
}  // namespace lightcone
