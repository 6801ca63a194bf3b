#pragma once
// Elastic material of two quasi-identical half-spaces (METHOD.md §2): the normal and
// tangential problems decouple and one shear modulus G and Poisson ratio nu describe both.
#include <cmath>

namespace railcontact {

struct Material {
  double youngs_modulus_Pa = 2.1e11;
  double poisson_ratio = 0.3;

  // G = E / (2 (1 + nu)) for equal materials.
  [[nodiscard]] double shear_modulus_Pa() const { return youngs_modulus_Pa / (2.0 * (1.0 + poisson_ratio)); }
  // Combined plane-strain modulus E* = E / (2 (1 - nu^2)) of two equal bodies (Hertz).
  [[nodiscard]] double contact_modulus_Pa() const {
    return youngs_modulus_Pa / (2.0 * (1.0 - poisson_ratio * poisson_ratio));
  }
  // Builds a material from G and nu.
  static Material from_shear_modulus(double shear_modulus_Pa, double nu) {
    return Material{2.0 * shear_modulus_Pa * (1.0 + nu), nu};
  }
};

// Throws railcontact::Error unless E > 0 (finite) and 0 <= nu < 0.5.
void validate(const Material& material);

}  // namespace railcontact
