#pragma once
// Matrix-free Krylov solves with Eigen's GMRES (unsupported IterativeSolvers module; chosen
// against BiCGSTAB and IDR(s) by measurement, docs/DEPENDENCIES.md): the operator and the preconditioner
// are callables y = M x, wrapped as Eigen matrix-free types (Eigen's documented pattern).
#include <Eigen/Core>
#include <functional>
#include <type_traits>
#include <unsupported/Eigen/IterativeSolvers>

namespace railcontact {

using ApplyFunction = std::function<void(const double* x, double* y)>;

class MatrixFreeOperator;

}  // namespace railcontact

namespace Eigen::internal {
template <>
struct traits<railcontact::MatrixFreeOperator> : public traits<Eigen::SparseMatrix<double>> {};
}  // namespace Eigen::internal

namespace railcontact {

class MatrixFreeOperator : public Eigen::EigenBase<MatrixFreeOperator> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic, IsRowMajor = false };

  MatrixFreeOperator(Eigen::Index size, ApplyFunction apply) : size_(size), apply_(std::move(apply)) {}
  [[nodiscard]] Eigen::Index rows() const { return size_; }
  [[nodiscard]] Eigen::Index cols() const { return size_; }

  template <typename Rhs>
  Eigen::Product<MatrixFreeOperator, Rhs, Eigen::AliasFreeProduct> operator*(const Eigen::MatrixBase<Rhs>& x) const {
    return Eigen::Product<MatrixFreeOperator, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }
  void apply(const double* x, double* y) const { apply_(x, y); }

 private:
  Eigen::Index size_;
  ApplyFunction apply_;
};

struct KrylovOptions {
  double tolerance = 1e-10;  // relative residual ||b - M x|| / ||b||
  int max_iterations = 500;
  int gmres_restart = 60;
  // Recompute the true residual after the solve (one more product) rather than take GMRES's
  // own estimate, which equals it up to rounding: worth it only for tolerances near rounding.
  bool recompute_residual = true;
};

struct KrylovReport {
  int iterations = 0;
  double relative_residual = 0.0;  // true residual (recomputed, or GMRES's estimate of it)
  bool converged = false;
};

// Solves M x = b from the initial guess in x.
KrylovReport solve_krylov(const MatrixFreeOperator& M, const ApplyFunction& preconditioner, const Eigen::VectorXd& b,
                          Eigen::VectorXd& x, const KrylovOptions& options);

}  // namespace railcontact

namespace Eigen::internal {
template <typename Rhs>
struct generic_product_impl<railcontact::MatrixFreeOperator, Rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<railcontact::MatrixFreeOperator, Rhs,
                                generic_product_impl<railcontact::MatrixFreeOperator, Rhs>> {
  using Scalar = typename Product<railcontact::MatrixFreeOperator, Rhs>::Scalar;
  // dst = M x, written in place when dst is a plain vector (GMRES's products).
  template <typename Dest>
  static void evalTo(Dest& dst, const railcontact::MatrixFreeOperator& lhs, const Rhs& rhs) {
    if constexpr (std::is_same_v<Dest, Eigen::VectorXd>) {
      const Eigen::Ref<const Eigen::VectorXd> x(rhs);
      dst.resize(x.size());
      // GMRES multiplies its zero initial guess too: that product is zero, and costs nothing here.
      if (x.isZero(0.0)) {
        dst.setZero();
        return;
      }
      lhs.apply(x.data(), dst.data());
    } else {
      dst.setZero();
      scaleAndAddTo(dst, lhs, rhs, Scalar(1));
    }
  }
  template <typename Dest>
  static void scaleAndAddTo(Dest& dst, const railcontact::MatrixFreeOperator& lhs, const Rhs& rhs,
                            const Scalar& alpha) {
    const Eigen::Ref<const Eigen::VectorXd> x(rhs);
    if (x.isZero(0.0)) return;
    Eigen::VectorXd y(x.size());
    lhs.apply(x.data(), y.data());
    dst += alpha * y;
  }
};
}  // namespace Eigen::internal
