// Solves on several threads at once (a multibody code evaluating its wheels in parallel): every
// thread plans FFTW transforms of its own sizes while the others plan and execute theirs. The
// results must equal the same solves run one after the other.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "elastic/influence_operator.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/contact_patch.hpp"

namespace railcontact {
namespace {

const Material kSteel{2.1e11, 0.3};

// Products of steady-rolling operators on meshes of many sizes (each a new transform size, so
// each plans), summed into one number per worker.
double operator_products(int worker) {
  double sum = 0.0;
  for (int n = 6 + worker; n < 60; n += 4) {
    Mesh mesh;
    mesh.n1 = n;
    mesh.n2 = n + 3;
    mesh.dx1_m = 1e-4;
    mesh.dx2_m = 1.5e-4;
    InfluenceOperator R = make_steady_rolling_operator(mesh, kSteel, 0.0);
    std::vector<std::size_t> elements(mesh.size());
    for (std::size_t k = 0; k < elements.size(); ++k) elements[k] = k;
    std::vector<double> x(2 * mesh.size()), y(2 * mesh.size());
    for (std::size_t k = 0; k < x.size(); ++k) x[k] = static_cast<double>(k % 13) - 6.0;
    R.apply(elements, x, y);
    for (double v : y) sum += v;
  }
  return sum;
}

TEST(Concurrency, OperatorsPlannedOnFourThreadsEqualSerialOnes) {
  constexpr int kWorkers = 4;
  std::vector<double> serial(kWorkers), parallel(kWorkers);
  for (int w = 0; w < kWorkers; ++w) serial[w] = operator_products(w);
  for (int round = 0; round < 3; ++round) {
    std::vector<std::thread> threads;
    for (int w = 0; w < kWorkers; ++w) threads.emplace_back([w, &parallel] { parallel[w] = operator_products(w); });
    for (std::thread& t : threads) t.join();
    for (int w = 0; w < kWorkers; ++w) EXPECT_NEAR(parallel[w], serial[w], 1e-12 * std::abs(serial[w])) << w;
  }
}

struct PatchResults {
  Flexibility flexibility;
  TangentialForces exact;
};

PatchResults solve_patch(int elements) {
  const double a = 6e-3, b = 4e-3;
  const ContactPatch patch = hertzian_patch(elliptical_contact_with_count(a, b, elements), a, b, 8e4, kSteel);
  PatchResults r;
  r.flexibility = NhFastSim(patch).flexibility();
  r.exact = solve_rolling_exact(patch, Creepage{1e-3, -5e-4, 0.5}, 0.3).forces;
  return r;
}

TEST(Concurrency, NhFastSimAndExactOnTwoThreadsEqualSerial) {
  const int sizes[] = {300, 700};
  PatchResults serial[2], parallel[2];
  for (int i = 0; i < 2; ++i) serial[i] = solve_patch(sizes[i]);
  std::thread other([&] { parallel[1] = solve_patch(sizes[1]); });
  parallel[0] = solve_patch(sizes[0]);
  other.join();
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(parallel[i].flexibility.L1, serial[i].flexibility.L1, 1e-9 * serial[i].flexibility.L1);
    EXPECT_NEAR(parallel[i].flexibility.L3, serial[i].flexibility.L3, 1e-9 * serial[i].flexibility.L3);
    EXPECT_NEAR(parallel[i].exact.F1_N, serial[i].exact.F1_N, 1e-9 * std::abs(serial[i].exact.F1_N));
    EXPECT_NEAR(parallel[i].exact.F2_N, serial[i].exact.F2_N, 1e-9 * std::abs(serial[i].exact.F2_N));
  }
}

}  // namespace
}  // namespace railcontact
