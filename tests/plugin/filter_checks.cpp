#include "filter_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <QRegularExpression>

#include <common/filterscript.h>

#include "core/geometry/welded_view.h"
#include "support/source_paths.h"
#include "vcg_adapters/surface_adapter.h"

namespace slim::test {

std::vector<vcg::Point3f> positions(const MeshModel& m) {
  std::vector<vcg::Point3f> p;
  for (const auto& v : m.cm.vert) p.push_back(v.cP());
  return p;
}

void expect_overhang_written(const MeshModel& m, const OverhangReport& expected) {
  ASSERT_TRUE(m.hasDataMask(MeshModel::MM_FACEQUALITY));
  ASSERT_TRUE(m.hasDataMask(MeshModel::MM_FACECOLOR));
  ASSERT_EQ(static_cast<size_t>(m.cm.fn), expected.risky.size());
  int selected = 0;
  for (int f = 0; f < m.cm.fn; ++f) {
    const CFaceO& face = m.cm.face[static_cast<size_t>(f)];
    EXPECT_NEAR(face.cQ(), expected.quality(f), 1e-5);
    EXPECT_EQ(face.IsS(), expected.risky[static_cast<size_t>(f)]);
    selected += face.IsS();
    // Faces near the threshold are green, with neither red nor blue.
    if (expected.quality(f) < -0.1) {
      EXPECT_GT(face.cC()[0], face.cC()[2]);
    } else if (expected.quality(f) > 0.1) {
      EXPECT_GT(face.cC()[2], face.cC()[0]);
    }
  }
  EXPECT_EQ(selected, expected.risky_count);
}

void expect_slimmed_layer(const MeshModel& input, const MeshModel& out, const std::vector<vcg::Point3f>& original,
                          double plate_tolerance, const QStringList& log) {
  ASSERT_NE(&out, &input);
  EXPECT_EQ(positions(input), original);  // the input layer is untouched
  EXPECT_FALSE(input.hasDataMask(MeshModel::MM_FACEQUALITY));
  EXPECT_EQ(out.label(), input.label() + "_slimmed");  // the tests' labels have no file extension
  EXPECT_EQ(out.cm.fn, input.cm.fn);
  ASSERT_EQ(out.cm.vn, input.cm.vn);
  EXPECT_NE(positions(out), original);
  ASSERT_TRUE(out.hasDataMask(MeshModel::MM_FACEQUALITY));
  ASSERT_TRUE(out.hasDataMask(MeshModel::MM_VERTQUALITY));

  // Quality, selection and vertex quality say what the core says about the new shape.
  PrintSetup o;
  o.plate = PlateRule::within(plate_tolerance);
  const OverhangReport now = analyse_overhang(vcg_adapters::to_surface(out.cm), o);
  const OverhangReport before = analyse_overhang(vcg_adapters::to_surface(input.cm), o);
  EXPECT_LT(now.risky_area, before.risky_area);
  int selected = 0;
  for (int f = 0; f < out.cm.fn; ++f) {
    EXPECT_NEAR(out.cm.face[static_cast<size_t>(f)].cQ(), now.quality(f), 1e-4);
    selected += out.cm.face[static_cast<size_t>(f)].IsS();
  }
  EXPECT_NEAR(selected, now.risky_count, 3);  // float rounding right at the threshold
  for (int v = 0; v < out.cm.vn; ++v) {
    const auto& vert = out.cm.vert[static_cast<size_t>(v)];
    EXPECT_NEAR(vert.cQ(), (vert.cP() - original[static_cast<size_t>(v)]).Norm(), 1e-4);
  }
  const QString text = log.join("\n");
  EXPECT_TRUE(text.contains("risky area")) << text.toStdString();
  EXPECT_TRUE(text.contains("inverted tets 0")) << text.toStdString();
}

void expect_oriented_layer(const MeshModel& input, const MeshModel& out, const std::vector<vcg::Point3f>& original,
                           const OrientationOptions& options, const QStringList& log) {
  ASSERT_NE(&out, &input);
  EXPECT_EQ(positions(input), original);  // the input layer is untouched
  EXPECT_EQ(out.label(), input.label() + "_oriented");
  const Surface seen = vcg_adapters::to_surface(input.cm);  // float positions, as the filter saw them
  const Surface got = vcg_adapters::to_surface(out.cm);
  ASSERT_EQ(got.F, seen.F);  // orienting never adds, removes or reorders a face
  const OrientationResult best = optimize_orientation(weld_coincident(seen).surface, options);  // as the filter computes
  const Surface expected = apply_orientation(seen, best.rotation);
  const double size = (seen.V.colwise().maxCoeff() - seen.V.colwise().minCoeff()).norm();
  EXPECT_LT((got.V - expected.V).cwiseAbs().maxCoeff(), 1e-5 * size);
  EXPECT_NEAR(got.V.col(2).minCoeff(), 0.0, 1e-6 * size);  // resting on the plate

  // Face quality and selection describe the new pose.
  ASSERT_TRUE(out.hasDataMask(MeshModel::MM_FACEQUALITY));
  const OverhangReport now = print_pose_overhang(got, best, options.alpha_max_deg);
  int selected = 0;
  for (int f = 0; f < out.cm.fn; ++f) {
    EXPECT_NEAR(out.cm.face[static_cast<size_t>(f)].cQ(), now.quality(f), 1e-4);
    selected += out.cm.face[static_cast<size_t>(f)].IsS();
  }
  EXPECT_NEAR(selected, now.risky_count, 3);  // float rounding right at the threshold

  const QString text = log.join("\n");
  for (const char* part : {"print direction (", "support proxy", "risky area", "  1. support", "  5. support", "as given: support"})
    EXPECT_TRUE(text.contains(part)) << part << " not in\n" << text.toStdString();
  EXPECT_FALSE(text.contains("  6. support")) << text.toStdString();
  // The poses are listed by the model's estimate: the chosen first (the least, or a pose that
  // stands within 5% of it), then the others, least support first.
  std::vector<double> listed;
  QRegularExpressionMatchIterator it = QRegularExpression("  \\d\\. support ([-+.0-9eE]+) mm").globalMatch(text);
  while (it.hasNext()) listed.push_back(it.next().captured(1).toDouble());
  ASSERT_EQ(listed.size(), 5u) << text.toStdString();
  EXPECT_TRUE(std::is_sorted(listed.begin() + 1, listed.end())) << text.toStdString();
  EXPECT_LE(listed[0], *std::min_element(listed.begin() + 1, listed.end()) * 1.05 + 1.0) << text.toStdString();
}

RichParameterList example_script_params(const QString& file, const QString& filter) {
  FilterScript script;
  EXPECT_TRUE(script.open(QString::fromStdString(source_dir()) + "/examples/" + file)) << file.toStdString();
  for (const auto& entry : script)
    if (entry.filterName() == filter) return entry.second;
  ADD_FAILURE() << filter.toStdString() << " not in " << file.toStdString();
  return {};
}

int progress_reports = 0;

bool cancel_at_second_report(int, const char*) { return ++progress_reports < 2; }

double dialog_budget_mm(const DeviationBudget& budget, const Surface& s) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (Eigen::Index v = 0; v < s.V.rows(); ++v)
    if (s.V.row(v).allFinite()) lo = lo.cwiseMin(s.V.row(v).transpose()), hi = hi.cwiseMax(s.V.row(v).transpose());
  return lo.x() <= hi.x() ? budget.mm((hi - lo).norm()).value_or(0.0) : 0.0;
}

}  // namespace slim::test
