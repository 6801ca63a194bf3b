#include <gtest/gtest.h>

#include "railcontact/error.hpp"
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

}  // namespace
}  // namespace railcontact
