// brdf::SpherePsnr (what reconstruct states about a glTF version) is the sphere test's own
// figure: the same protocol gives the same numbers as evaluate::SphereTest.
#include "brdf/sphere_figure.h"

#include <gtest/gtest.h>

#include "brdf/analytic.h"
#include "evaluate/sphere_test.h"

namespace brdfrig::brdf {
namespace {

TEST(SphereFigureTest, EqualsTheSphereTestsPsnr) {
  const Ggx truth({Rgb(0.3, 0.2, 0.1), Rgb(0.04, 0.04, 0.04), 0.2});
  const CookTorrance fitted({Rgb(0.28, 0.21, 0.1), Rgb(0.05, 0.04, 0.04), 0.23});
  const SphereFigure figure = SpherePsnr(truth, fitted);
  const evaluate::SphereTestResult reference = evaluate::SphereTest(truth, fitted);
  ASSERT_EQ(figure.psnr_db.size(), reference.lights.size());
  for (std::size_t i = 0; i < figure.psnr_db.size(); ++i) {
    EXPECT_NEAR(figure.psnr_db[i], reference.lights[i].psnr_db, 1e-9);
  }
  EXPECT_NEAR(figure.mean_psnr_db, reference.mean_psnr_db, 1e-9);
  EXPECT_NEAR(figure.worst_psnr_db, reference.worst_psnr_db, 1e-9);
}

}  // namespace
}  // namespace brdfrig::brdf
