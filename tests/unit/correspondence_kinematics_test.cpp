// Correspondence kinematics (Foster, Silling & Chen 2010 eqs 10, 13, 14): F and Ḟ are exact for affine
// motions at every point, boundaries included, on jittered lattices, with partial volumes and every
// influence function (the proof after eq 13); a singular shape tensor is reported, not turned into NaNs;
// the mid-step L of a rigid rotation is skew.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "peridot/core/error.hpp"
#include "peridot/correspondence/kinematics.hpp"
#include "support/correspondence_cloud.hpp"

namespace peridot {
namespace {

using correspondence::KinematicFields;
using correspondence::Mat3;

Mat3 random_matrix(std::uint64_t& seed, double amplitude) {
  Mat3 a;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a(r, c) = amplitude * (2 * uniform01(seed) - 1);
  return a;
}

struct AffineCase {
  double jitter;
  bool partial_volume;
  InfluenceKind influence;
};

TEST(CorrKinematics, DeformationGradientAndRateExactForAffineMotionAtEveryPoint) {
  const AffineCase cases[] = {{0.0, false, InfluenceKind::constant},
                              {0.25, false, InfluenceKind::constant},
                              {0.25, true, InfluenceKind::inverse_distance},
                              {0.25, true, InfluenceKind::gaussian}};
  std::uint64_t seed = 42;
  for (const AffineCase& c : cases) {
    testing::CloudSetup setup;
    setup.jitter = c.jitter;
    setup.partial_volume = c.partial_volume;
    setup.influence = c.influence;
    auto cloud = testing::make_cloud(setup);
    const Discretization& disc = cloud->disc;
    const std::size_t n = disc.num_points();
    // A finite, non-symmetric F (|F − I| up to 0.3 per entry, det > 0) and an arbitrary Ḟ.
    const Mat3 F = Mat3::Identity() + random_matrix(seed, 0.3);
    ASSERT_GT(F.determinant(), 0);
    const Mat3 F_rate = random_matrix(seed, 1e3);  // 1/s
    const correspondence::Vec3d translation(1e-3, -2e-3, 5e-4), velocity(3, -1, 2);
    VectorField u(n), v(n);
    for (std::size_t i = 0; i < n; ++i) {
      const correspondence::Vec3d x(disc.x(i, 0), disc.x(i, 1), disc.x(i, 2));
      const correspondence::Vec3d ui = (F - Mat3::Identity()) * x + translation;
      const correspondence::Vec3d vi = F_rate * x + velocity;
      for (int d = 0; d < 3; ++d) {
        u(i, d) = ui(d);
        v(i, d) = vi(d);
      }
    }
    KinematicFields kin;
    correspondence::compute_kinematics(cloud->ctx, u, v, kin);
    double worst_F = 0, worst_rate = 0;
    std::size_t surface_points = 0;
    for (std::size_t i = 0; i < n; ++i) {
      worst_F = std::max(worst_F, (kin.deformation_gradient.get(i) - F).cwiseAbs().maxCoeff());
      worst_rate = std::max(worst_rate, (kin.deformation_gradient_rate.get(i) - F_rate).cwiseAbs().maxCoeff());
      if (testing::distance_to_surface(*cloud, setup.cells, i) < cloud->horizon) ++surface_points;
    }
    std::printf("affine F: jitter %.2f, partial volume %d, influence %d: max |F − F_exact| %.2e, "
                "max |Ḟ − Ḟ_exact| %.2e /s, %zu of %zu points within δ of the surface\n",
                c.jitter, c.partial_volume, static_cast<int>(c.influence), worst_F, worst_rate, surface_points, n);
    SCOPED_TRACE("jitter " + std::to_string(c.jitter) + ", partial volume " + std::to_string(c.partial_volume) +
                 ", influence " + std::to_string(static_cast<int>(c.influence)));
    // Every point of the 7³ box is checked; most of them (all but the 1³ core) lack part of their family.
    EXPECT_EQ(n, 343u);
    EXPECT_GT(surface_points, 300u);
    // Exact up to round-off: the error is that of summing ~100 bond terms and inverting K.
    EXPECT_LT(worst_F, 1e-13);
    EXPECT_LT(worst_rate, 1e-13 * 1e3);
  }
}

TEST(CorrKinematics, CoplanarPointsAreReportedAsSingularShapeTensor) {
  // One layer of points: every bond lies in the plane z = ½Δx, so K has a zero eigenvalue everywhere.
  testing::CloudSetup setup;
  setup.cells[2] = 1;
  auto cloud = testing::make_cloud(setup);
  const std::size_t n = cloud->disc.num_points();
  VectorField u(n), v(n);
  KinematicFields kin;
  try {
    correspondence::compute_kinematics(cloud->ctx, u, v, kin);
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    const std::string message = e.what();
    // The lowest-numbered point is named, with its position.
    EXPECT_NE(message.find("point 0 "), std::string::npos) << message;
    EXPECT_NE(message.find(fmt::format("({:g}, {:g}, {:g}) m", cloud->disc.x(0, 0), cloud->disc.x(0, 1),
                                       cloud->disc.x(0, 2))),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("non-coplanar"), std::string::npos) << message;
  }
}

TEST(CorrKinematics, PointLeftWithTwoIntactBondsIsReported) {
  // A unit tetrahedron, every pair bonded: each point has three non-coplanar bonds and F is computed.
  Discretization disc;
  disc.dimension = 3;
  disc.x.resize(4);
  disc.x.set(1, {1e-3, 0, 0});
  disc.x.set(2, {0, 1e-3, 0});
  disc.x.set(3, {0, 0, 1e-3});
  disc.volume.assign(4, 1e-9);
  disc.block.assign(4, 0);
  disc.input_id = {0, 1, 2, 3};
  disc.block_names = {"tet"};
  NeighborhoodOptions options;
  options.horizon_of_block = {2e-3};
  BondList bonds = build_neighborhood(disc, options);
  ASSERT_EQ(bonds.num_bonds(), 12u);
  build_reverse_bonds(bonds);
  auto ctx = correspondence::make_correspondence_context(disc, bonds, {{2e-3, InfluenceKind::constant}});
  VectorField u(4), v(4);
  KinematicFields kin;
  ASSERT_NO_THROW(correspondence::compute_kinematics(ctx, u, v, kin));
  EXPECT_LT((kin.deformation_gradient.get(0) - Mat3::Identity()).norm(), 1e-15);

  // Break the bond 0–3 (both directions): points 0 and 3 keep two bonds each, which span a plane.
  for (std::size_t i : {0u, 3u})
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b)
      if (bonds.neighbors[b] == 3 - i) bonds.broken[b] = 1;
  try {
    correspondence::compute_kinematics(ctx, u, v, kin);
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("point 0 (input id 0) at (0, 0, 0) m"), std::string::npos) << message;
    EXPECT_NE(message.find("2 intact bonds"), std::string::npos) << message;
  }
}

TEST(CorrKinematics, MidStepVelocityGradientOfRigidRotationIsSkew) {
  std::uint64_t seed = 7;
  for (int trial = 0; trial < 20; ++trial) {
    // Two unrelated finite rotations: the step's rotation need not be small or about a fixed axis.
    const correspondence::Vec3d a = random_matrix(seed, 1.0).col(0), b = random_matrix(seed, 2.0).col(0);
    const Mat3 R0 = Eigen::AngleAxisd(a.norm(), a.normalized()).toRotationMatrix();
    const Mat3 R1 = Eigen::AngleAxisd(b.norm(), b.normalized()).toRotationMatrix();
    const double dt = 1e-3;
    const Mat3 L = correspondence::mid_step_velocity_gradient(R1, (R1 - R0) / dt, dt);
    EXPECT_LT((L + L.transpose()).norm(), 1e-13 * L.norm());
  }
}

}  // namespace
}  // namespace peridot
