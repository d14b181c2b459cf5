// The prior rung's energy step: a table that reflects more than it receives is scaled down
// where it does, within the limit, its colour kept; a table within the limit is left alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "brdf/rusinkiewicz_table.h"
#include "common/angles.h"
#include "reconstruct/energy.h"

namespace brdfrig::reconstruct {
namespace {

brdf::RusinkiewiczGrid SmallGrid() {
  brdf::RusinkiewiczGrid g;
  g.theta_h = 24;
  g.theta_d = 12;
  g.phi_d = 4;
  return g;
}

// A table of f = albedo(node) / π at every node (Lambertian where albedo is constant).
brdf::TableValues TableOf(const brdf::RusinkiewiczGrid& g,
                          const std::function<double(const brdf::HalfDiffAngles&)>& albedo) {
  brdf::TableValues q;
  for (auto& channel : q) channel.resize(static_cast<std::size_t>(g.Cells()));
  for (int ih = 0; ih < g.theta_h; ++ih) {
    for (int id = 0; id < g.theta_d; ++id) {
      for (int ip = 0; ip < g.phi_d; ++ip) {
        const brdf::HalfDiffAngles a = brdf::NodeAngles(g, ih, id, ip);
        brdf::Vec3 l, v;
        brdf::FromHalfDiffAngles(a, &l, &v);
        const double c = brdf::CosineProduct(g, l, v);
        // Green is half as bright as red and blue: its albedo alone stays within the limit.
        for (int ch = 0; ch < 3; ++ch) {
          q[ch][g.Index(ih, id, ip)] = brdf::MapValue(g, albedo(a) / M_PI * (ch == 1 ? 0.5 : 1), c);
        }
      }
    }
  }
  return q;
}

// The largest albedo of any channel at 0°, 5°, …, 85°.
double PeakAlbedo(const brdf::RusinkiewiczGrid& g, const brdf::TableValues& q) {
  const brdf::RusinkiewiczTable table(g, q);
  double peak = 0;
  for (int deg = 0; deg <= 85; deg += 5) {
    peak = std::max(peak, HalfVectorAlbedo(table, Radians(deg)).maxCoeff());
  }
  return peak;
}

// Everything past θd 50° four times as bright as the rest: the table reflects more than it
// receives towards grazing incidence, as a prior extrapolating there can.
double BrightPastFifty(const brdf::HalfDiffAngles& a) {
  return a.theta_d > Radians(50) ? 3.2 : 0.8;
}

// f per node of one channel (q unmapped without the cosines, which cancel in a ratio).
double Level(const brdf::RusinkiewiczGrid& g, const brdf::TableValues& q, int ch, int node) {
  return std::exp(q[ch][node]) - g.epsilon;
}

TEST(TableEnergyTest, AnOverBrightTableIsScaledWithinTheLimitKeepingItsColour) {
  const brdf::RusinkiewiczGrid g = SmallGrid();
  const brdf::TableValues before = TableOf(g, BrightPastFifty);
  ASSERT_GT(PeakAlbedo(g, before), 1.2);  // the case this test is about
  brdf::TableValues after = before;
  const double scale = LimitTableEnergy(g, &after);

  EXPECT_LE(PeakAlbedo(g, after), 1.0);
  EXPECT_GT(PeakAlbedo(g, after), 0.9);  // scaled by the excess, not emptied
  EXPECT_GT(scale, 1.2);
  int lowered = 0;
  for (int node = 0; node < g.Cells(); ++node) {
    EXPECT_LE(after[0][node], before[0][node]);
    lowered += after[0][node] < before[0][node];
    // Every channel by the same factor: green stays half of red.
    const double red = Level(g, after, 0, node), green = Level(g, after, 1, node);
    if (red > 1e-3) {
      EXPECT_NEAR(green / red, 0.5, 1e-3) << "node " << node;
    }
  }
  EXPECT_GT(lowered, 0);
  // Light at the normal sees θd up to 45° only: its albedo was within the limit, and the node
  // of normal incidence and exitance keeps its value.
  EXPECT_EQ(after[0][g.Index(0, 0, 0)], before[0][g.Index(0, 0, 0)]);
}

TEST(TableEnergyTest, ATableWithinTheLimitIsLeftAlone) {
  const brdf::RusinkiewiczGrid g = SmallGrid();
  const brdf::TableValues before = TableOf(g, [](const brdf::HalfDiffAngles&) { return 0.9; });
  brdf::TableValues after = before;
  EXPECT_EQ(LimitTableEnergy(g, &after), 1);
  EXPECT_EQ(after, before);
}

}  // namespace
}  // namespace brdfrig::reconstruct
