// The study's summary of held-out figures when some views have no normalized figure (the truth
// black over the sample, evaluate/sample_figures.h): built from rows, no capture.
#include <gtest/gtest.h>

#include <cmath>

#include "jobs/material_study.h"

namespace brdfrig::jobs {
namespace {

MaterialStudyRow Row(const std::string& name, double held_mean, int defined_views) {
  MaterialStudyRow row;
  row.material.name = name;
  row.result.figures.held_out.resize(4);
  row.held_out_views = defined_views;
  RungRow rung;
  rung.kind = "prior";
  rung.fitted = true;
  rung.chosen = true;
  rung.sphere_mean_db = 30;
  rung.held_out_mean_db = held_mean;
  rung.held_out_min_db = held_mean;
  row.rungs = {rung};
  row.chosen = row.best = 0;
  return row;
}

TEST(StudySummary, MaterialsWithoutAHeldOutFigureAreCountedNotHidden) {
  // b's views are all black (no held-out mean), c's one of four.
  const std::vector<MaterialStudyRow> rows = {Row("a", 30, 4), Row("b", NAN, 0), Row("c", 34, 3)};
  const RungSummary s = SummarizeRung(rows, "prior", 0.1);
  EXPECT_EQ(s.materials, 3);
  EXPECT_EQ(s.held_out_materials, 2);
  EXPECT_DOUBLE_EQ(s.held_out_mean_db, 32);
  const std::string table = LadderMarkdown(rows, StudyPlan{"test", {}}, 0.1);
  EXPECT_NE(table.find("| 32.0 (over 2) |"), std::string::npos) << table;
  EXPECT_NE(table.find("b 4 of 4, c 1 of 4"), std::string::npos) << table;
}

}  // namespace
}  // namespace brdfrig::jobs
