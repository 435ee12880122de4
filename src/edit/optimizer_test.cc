#include "edit/optimizer.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace isegman::edit {
namespace {

TEST(Optimizer, ScheduleStartsAtOneAndReachesZeroAtTheLastStep) {
  for (Schedule s : {Schedule::kCosine, Schedule::kLinear}) {
    EXPECT_DOUBLE_EQ(schedule_factor(s, 0, 1500), 1.0);
    EXPECT_NEAR(schedule_factor(s, 1499, 1500), 0.0, 1e-12);
    double prev = 2;
    for (int t = 0; t < 1500; t += 50) {
      const double f = schedule_factor(s, t, 1500);
      EXPECT_LT(f, prev);
      prev = f;
    }
  }
  EXPECT_NEAR(schedule_factor(Schedule::kCosine, 750, 1501), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(schedule_factor(Schedule::kConstant, 1499, 1500), 1.0);
  EXPECT_EQ(parse_schedule("linear"), Schedule::kLinear);
  EXPECT_THROW(parse_schedule("exp"), Error);
}

TEST(Optimizer, AdamMovesOnlySelectedGaussiansAgainstTheGradient) {
  GaussianScene s;
  s.resize(4, 1);
  for (size_t i = 0; i < 4; ++i) s.positions[3 * i] = float(i);
  const GaussianScene before = s;
  LearningRates lr;
  SelectionAdam adam(s, {1, 3}, lr, 2.0);
  EXPECT_EQ(adam.slots()[0], -1);
  EXPECT_EQ(adam.slots()[3], 1);
  GaussianGrads<float> g;
  g.resize(2, 1);
  g.positions[0] = 1.f;   // slot 0 = Gaussian 1, x
  g.sh[3 + 1] = -2.f;     // slot 0, rest coefficient 1, green
  g.opacity[1] = 0.5f;
  g.scales[3 * 1 + 2] = -1.f;
  g.rotations[4 * 1] = 3.f;
  adam.step(s, g, 1.0);
  // Adam's first step moves each parameter by lr * sign(gradient).
  EXPECT_NEAR(s.positions[3], before.positions[3] - 1.6e-4 * 2.0, 1e-7);
  EXPECT_NEAR(s.sh_of(1)[3 + 1], 0.0125 / 20, 1e-8);
  EXPECT_NEAR(s.opacity[3], -0.05, 1e-7);
  EXPECT_NEAR(s.scales[3 * 3 + 2], 5e-3, 1e-8);
  EXPECT_NEAR(s.rotations[4 * 3], 1.f - 1e-3, 1e-7);
  EXPECT_EQ(s.positions[0], before.positions[0]);
  EXPECT_EQ(s.positions[6], before.positions[6]);
  for (size_t i : {size_t(0), size_t(2)}) {
    EXPECT_EQ(s.opacity[i], before.opacity[i]);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(s.rotations[4 * i + k], before.rotations[4 * i + k]);
  }
  // A zero step size changes nothing.
  const GaussianScene mid = s;
  adam.step(s, g, 0.0);
  EXPECT_EQ(s.positions, mid.positions);
  EXPECT_THROW(SelectionAdam(s, {1, 1}, lr, 1.0), Error);
}

}  // namespace
}  // namespace isegman::edit
