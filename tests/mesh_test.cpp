#include <gtest/gtest.h>

#include <vector>

#include "railcontact/error.hpp"
#include "mesh/element_rows.hpp"
#include "railcontact/contact_patch.hpp"

namespace railcontact {
namespace {

TEST(Mesh, CoveringPlacesElementCentres) {
  const Mesh mesh = Mesh::covering(-1.0, 1.0, -2.0, 2.0, 4, 8);
  EXPECT_DOUBLE_EQ(mesh.dx1_m, 0.5);
  EXPECT_DOUBLE_EQ(mesh.dx2_m, 0.5);
  EXPECT_DOUBLE_EQ(mesh.x1(0), -0.75);
  EXPECT_DOUBLE_EQ(mesh.x1(3), 0.75);
  EXPECT_DOUBLE_EQ(mesh.x2(7), 1.75);
  EXPECT_EQ(mesh.index(1, 2), 9u);
}

TEST(Mesh, RejectsTooLargeMesh) {
  Mesh mesh = Mesh::covering(0, 1, 0, 1, 100000, 100000);
  EXPECT_THROW(validate(mesh), Error);
}

// ElementRows gives (k mod n1, k / n1) for elements in any order: row by row (one division per
// row), backwards, jumping between rows, repeated, at a row's first and last element.
TEST(Mesh, ElementRowsAreTheIndexsColumnAndRow) {
  for (const std::size_t n1 : {std::size_t{1}, std::size_t{7}, std::size_t{96}}) {
    std::vector<std::size_t> order;
    for (std::size_t k = 0; k < 40 * n1; k += 3) order.push_back(k);
    for (std::size_t k = 40 * n1; k-- > 0;) order.push_back(k);
    for (const std::size_t k : {std::size_t{5}, 33 * n1, 33 * n1, n1 - 1, n1, 2 * n1 - 1, std::size_t{0}, 1000 * n1 + 3})
      order.push_back(k);
    detail::ElementRows rows(n1);
    for (const std::size_t k : order) {
      const auto [i1, i2] = rows.at(k);
      ASSERT_EQ(static_cast<std::size_t>(i1), k % n1) << "n1 = " << n1 << ", k = " << k;
      ASSERT_EQ(static_cast<std::size_t>(i2), k / n1) << "n1 = " << n1 << ", k = " << k;
    }
  }
}

}  // namespace
}  // namespace railcontact
