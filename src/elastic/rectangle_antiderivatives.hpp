#pragma once
// Antiderivatives F(X, Y), d2F/dXdY = k(X, Y), of the half-space kernels (METHOD.md §4),
// evaluated at one corner offset (X, Y) = point - corner. The integral of k over a rectangle
// is F(pp) - F(mp) - F(pm) + F(mm) over its corners. The X ln|X| terms of the classical
// forms cancel between corners and are dropped, which keeps F finite on the element edges.
#include <cmath>

namespace railcontact {

struct RectangleAntiderivatives {
  double one_over_r;  // ∫∫ 1/r   = X asinh(Y/|X|) + Y asinh(X/|Y|)
  double x2_over_r3;  // ∫∫ X²/r³ = Y asinh(X/|Y|)
  double y2_over_r3;  // ∫∫ Y²/r³ = X asinh(Y/|X|)
  double xy_over_r3;  // ∫∫ XY/r³ = -r
};

// X asinh(Y/|X|), continuous with value 0 at X = 0.
inline double x_asinh_y_over_x(double X, double Y) {
  if (X == 0.0) return 0.0;
  return X * std::asinh(Y / std::fabs(X));
}

inline RectangleAntiderivatives rectangle_antiderivatives(double X, double Y) {
  const double xa = x_asinh_y_over_x(X, Y);
  const double ya = x_asinh_y_over_x(Y, X);
  return {xa + ya, ya, xa, -std::hypot(X, Y)};
}

}  // namespace railcontact
