#pragma once
// Rigid creepages of steady rolling (METHOD.md §2): xi, eta dimensionless, spin phi in 1/m.
// Forces follow Kalker's sign convention: F1 = -G c^2 C11 xi, etc.

namespace railcontact {

struct Creepage {
  double xi = 0.0;    // longitudinal creepage (-)
  double eta = 0.0;   // lateral creepage (-)
  double phi = 0.0;   // spin creepage (1/m)
};

// Tangential force and spin moment on the wheel (upper body), in the contact frame.
struct TangentialForces {
  double F1_N = 0.0;   // longitudinal force
  double F2_N = 0.0;   // lateral force
  double M3_Nm = 0.0;  // spin moment about X3 through the pressure centre
};

}  // namespace railcontact
