// Full-adhesion steady-state solver: K2 against Kalker's linear theory, the dense reference,
// Kalker's sign convention (Eq 16) and the symmetries of an elliptical patch.
#include <gtest/gtest.h>

#include <cmath>

#include "railcontact/tangential.hpp"
#include "railcontact/contact_patch.hpp"
#include "railcontact/error.hpp"
#include "tangential/adhesion_tuning.hpp"
#include "railcontact/kalker.hpp"

namespace railcontact {
namespace {

const Material kSteel{2.1e11, 0.3};

TEST(Adhesion, DenseAndKrylovAgree) {
  const ContactElements ellipse = elliptical_contact(5e-3, 3e-3, 24, 20);  // ~380 elements
  AdhesionOptions dense;
  dense.solver = LinearSolver::dense;
  AdhesionOptions krylov;
  krylov.tolerance = 1e-13;
  for (double alpha : {0.0, 0.5}) {
    dense.collocation_offset = krylov.collocation_offset = alpha;
    const Matrix3 K_dense = solve_full_adhesion(ellipse, kSteel, dense).creepage_matrix;
    const Matrix3 K_krylov = solve_full_adhesion(ellipse, kSteel, krylov).creepage_matrix;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double scale = std::sqrt(std::fabs(K_dense(i, i) * K_dense(j, j)));
        EXPECT_NEAR(K_krylov(i, j), K_dense(i, j), 1e-8 * scale) << i << "," << j << " alpha " << alpha;
      }
  }
}

TEST(Adhesion, CreepageMatrixHasKalkersSignPatternOnAnEllipse) {
  // Eq 16: K1 = [[-f11, 0, 0], [0, -f22, -f23], [0, f23, -f33]] with f > 0.
  const ContactElements ellipse = elliptical_contact_with_count(6e-3, 4e-3, 1500);
  const Matrix3 K = solve_full_adhesion(ellipse, kSteel).creepage_matrix;
  EXPECT_LT(K(0, 0), 0);
  EXPECT_LT(K(1, 1), 0);
  EXPECT_LT(K(2, 2), 0);
  EXPECT_LT(K(1, 2), 0);
  EXPECT_GT(K(2, 1), 0);
  // xi-eta and xi-phi couplings vanish by symmetry of the ellipse about x2 = 0.
  const double f11 = -K(0, 0), f22 = -K(1, 1);
  const double c = std::sqrt(6e-3 * 4e-3);
  EXPECT_LT(std::fabs(K(0, 1)), 1e-8 * f11);
  EXPECT_LT(std::fabs(K(1, 0)), 1e-8 * f11);
  EXPECT_LT(std::fabs(K(0, 2)), 1e-8 * f11 * c);
  EXPECT_LT(std::fabs(K(2, 0)), 1e-8 * f22 * c);
  // Kalker: M3 per eta equals minus F2 per phi (the reciprocal f23 terms), here within the
  // discretisation error of the first-order steady-state scheme.
  EXPECT_NEAR(K(2, 1), -K(1, 2), 0.05 * std::fabs(K(1, 2)));
}

TEST(Adhesion, TractionsVanishAtTheLeadingEdgeAndGrowTowardsTheTrailingEdge) {
  const ContactElements ellipse = elliptical_contact(6e-3, 6e-3, 40);
  const AdhesionSolution s = solve_full_adhesion(ellipse, kSteel);
  // Centre strip: p1 per unit xi is negative and its magnitude grows from the leading edge.
  const Mesh& mesh = ellipse.mesh();
  const auto& idx = ellipse.indices();
  std::vector<double> strip;
  for (std::size_t e = 0; e < idx.size(); ++e)
    if (static_cast<int>(idx[e] / mesh.n1) == mesh.n2 / 2) strip.push_back(s.unit_tractions(e, 0));
  ASSERT_GT(strip.size(), 10u);
  for (double p : strip) EXPECT_LT(p, 0.0);
  EXPECT_LT(std::fabs(strip.back()), 0.25 * std::fabs(strip.front()));  // leading edge (largest x1) small
}

struct KalkerCase {
  double a_over_b, nu;
};

class AdhesionAgainstKalker : public ::testing::TestWithParam<KalkerCase> {};

TEST_P(AdhesionAgainstKalker, CoefficientsWithinTwoPercentOfTheTable) {
  const KalkerCase c = GetParam();
  EllipseCoefficientOptions options;
  options.target_elements = 1500;
  const EllipseCoefficientResult r = ellipse_creepage_coefficients(c.a_over_b, c.nu, options);
  const KalkerCoefficients table = kalker_coefficients(c.a_over_b, c.nu);
  EXPECT_NEAR(r.coefficients.C11 / table.C11, 1.0, 0.02);
  EXPECT_NEAR(r.coefficients.C22 / table.C22, 1.0, 0.02);
  EXPECT_NEAR(r.coefficients.C23 / table.C23, 1.0, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Ellipses, AdhesionAgainstKalker,
                         ::testing::Values(KalkerCase{0.2, 0.0}, KalkerCase{0.5, 0.25}, KalkerCase{1.0, 0.25},
                                           KalkerCase{2.0, 0.25}, KalkerCase{5.0, 0.25}));

TEST(Adhesion, PaperConfigurationReproducesTable1Entry) {
  // Paper Table 1, a/b = 1, nu = 1/4, ~2800 elements, alpha = 0: 0.33%, 0.55%, 1.31%.
  EllipseCoefficientOptions paper;
  paper.layout = EllipseMeshLayout::equal_counts;
  paper.adhesion = AdhesionOptions{};
  const EllipseCoefficientResult r = ellipse_creepage_coefficients(1.0, 0.25, paper);
  EXPECT_NEAR(100 * (r.coefficients.C11 / 4.12 - 1), 0.33, 0.01);
  EXPECT_NEAR(100 * (r.coefficients.C22 / 3.67 - 1), 0.55, 0.01);
  EXPECT_NEAR(100 * (r.coefficients.C23 / 1.47 - 1), -1.31, 0.01);
}

TEST(Adhesion, ConvergesWithTheMeshOnACircle) {
  // Area-consistent c removes the staircase-area noise; the error then decreases with the mesh.
  EllipseCoefficientOptions options;
  options.c_from_discrete_area = true;
  const KalkerCoefficients table = kalker_coefficients(1.0, 0.25);
  double previous = 1.0;
  for (int n : {700, 2800, 11000}) {
    options.target_elements = n;
    const EllipseCoefficientResult r = ellipse_creepage_coefficients(1.0, 0.25, options);
    const double error = std::fabs(r.coefficients.C11 / table.C11 - 1) + std::fabs(r.coefficients.C22 / table.C22 - 1);
    EXPECT_LT(error, previous) << n;
    previous = error;
  }
  EXPECT_LT(previous, 0.006);
}

TEST(Adhesion, ReportsNonConvergenceInsteadOfReturningGarbage) {
  const ContactElements ellipse = elliptical_contact(6e-3, 4e-3, 30);
  AdhesionOptions options;
  options.max_iterations = 3;
  EXPECT_THROW(solve_full_adhesion(ellipse, kSteel, options), Error);
}

TEST(Adhesion, RejectsBadInput) {
  const ContactElements ellipse = elliptical_contact(6e-3, 4e-3, 20);
  AdhesionOptions bad_alpha;
  bad_alpha.collocation_offset = -1.0;  // centred difference: singular
  EXPECT_THROW(solve_full_adhesion(ellipse, kSteel, bad_alpha), Error);
  bad_alpha.collocation_offset = std::nan("");
  EXPECT_THROW(solve_full_adhesion(ellipse, kSteel, bad_alpha), Error);
  AdhesionTuning bad_gamma;
  bad_gamma.half_laplacian_gamma = 0.0;
  EXPECT_THROW(solve_full_adhesion(ellipse, kSteel, {}, bad_gamma), Error);
  bad_gamma.half_laplacian_gamma = std::nan("");
  EXPECT_THROW(solve_full_adhesion(ellipse, kSteel, {}, bad_gamma), Error);
  EXPECT_THROW(solve_full_adhesion(ellipse, Material{2.1e11, 0.51}, {}), Error);  // nu = 0.5 is valid
  EXPECT_THROW(solve_full_adhesion(ellipse, Material{-1.0, 0.3}, {}), Error);
  const Mesh mesh = Mesh::covering(0, 1, 0, 1, 4, 4);
  EXPECT_THROW(solve_full_adhesion(ContactElements(mesh, std::vector<std::uint8_t>(16, 0)), kSteel, {}), Error);
  EXPECT_THROW(ellipse_creepage_coefficients(1000.0, 0.3), Error);
  EXPECT_THROW(ellipse_creepage_coefficients(1.0, 0.51), Error);
  EXPECT_THROW(ellipse_creepage_coefficients(1.0, -0.1), Error);
  EXPECT_THROW(elliptical_contact(-1.0, 1.0, 10), Error);
}

}  // namespace
}  // namespace railcontact

namespace railcontact {
namespace {

TEST(Adhesion, ForceRowsByAdjointSolvesEqualTheFullMatrix) {
  const ContactElements patch = elliptical_contact_with_count(6e-3, 4e-3, 900, EllipseMeshLayout::rolling_resolved);
  AdhesionOptions full;
  full.tolerance = 1e-12;
  const Matrix3 K = solve_full_adhesion(patch, kSteel, full).creepage_matrix;
  for (LinearSolver solver : {LinearSolver::krylov, LinearSolver::dense}) {
    AdhesionOptions rows = full;
    rows.part = CreepageMatrixPart::force_rows;
    rows.solver = solver;
    const Matrix3 R = solve_full_adhesion(patch, kSteel, rows).creepage_matrix;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(R(i, j), K(i, j), 1e-8 * std::sqrt(std::fabs(K(i, i) * K(j, j)))) << i << j;
    EXPECT_TRUE(std::isnan(R(2, 2)));
  }
  AdhesionOptions mixed;
  mixed.part = CreepageMatrixPart::force_rows;
  mixed.spin_collocation_offset = 0.5;
  EXPECT_THROW(solve_full_adhesion(patch, kSteel, mixed), Error);
}

}  // namespace
}  // namespace railcontact
