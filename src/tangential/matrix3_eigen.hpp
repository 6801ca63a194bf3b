#pragma once
// The public 3 × 3 matrix (railcontact/tangential.hpp: K2, S D B) as an Eigen matrix for the
// library's own algebra, and back. The public headers do not include Eigen.
#include <Eigen/Core>

#include "railcontact/tangential.hpp"

namespace railcontact::detail {

inline Eigen::Matrix3d to_eigen(const Matrix3& m) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(m.values.data());
}

inline Matrix3 to_matrix3(const Eigen::Matrix3d& m) {
  Matrix3 out;
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(out.values.data()) = m;
  return out;
}

}  // namespace railcontact::detail
