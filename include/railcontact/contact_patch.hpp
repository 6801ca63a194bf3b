#pragma once
// Stage: contact patch types, shared by every solver.
// The material of two quasi-identical elastic half-spaces, the creepages and tangential forces of
// steady rolling, the regular mesh of the potential contact area, the elements in contact, and the
// contact patch (mesh + pressure + strip structure) the tangential solvers work on, with elliptical
// (Hertzian) patches and coarsening. Frame and signs: docs/CONVENTIONS.md; mesh: docs/METHOD.md §3.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

// Elastic material of two quasi-identical half-spaces (METHOD.md §2): the normal and
// tangential problems decouple and one shear modulus G and Poisson ratio nu describe both.

namespace railcontact {

struct Material {
  double youngs_modulus_Pa = 2.1e11;
  double poisson_ratio = 0.3;

  // G = E / (2 (1 + nu)) for equal materials.
  [[nodiscard]] double shear_modulus_Pa() const { return youngs_modulus_Pa / (2.0 * (1.0 + poisson_ratio)); }
  // Combined plane-strain modulus E* = E / (2 (1 - nu^2)) of two equal bodies (Hertz): finite for
  // every allowed nu, E* = 2E/3 for the incompressible nu = 0.5.
  [[nodiscard]] double contact_modulus_Pa() const {
    return youngs_modulus_Pa / (2.0 * (1.0 - poisson_ratio * poisson_ratio));
  }
  // Builds a material from G and nu.
  static Material from_shear_modulus(double shear_modulus_Pa, double nu) {
    return Material{2.0 * shear_modulus_Pa * (1.0 + nu), nu};
  }
};

// The physical range of Young's modulus: from soft polymers (1 MPa) to beyond diamond (1.2e12 Pa).
// Outside it the elastic constants are not those of a solid, and the solvers' numbers (tractions
// of G times a creepage, flexibilities of a/G) leave the range in which they are meaningful
// (E = 1e308 Pa gives flexibilities of 1e-322 m/Pa, denormal).
inline constexpr double kMinimumYoungsModulus_Pa = 1e6;
inline constexpr double kMaximumYoungsModulus_Pa = 1e13;

// Throws railcontact::Error (invalid_input) naming the value and the range unless E lies in
// [kMinimumYoungsModulus_Pa, kMaximumYoungsModulus_Pa] and 0 <= nu <= 0.5. nu = 0.5
// (incompressible) is valid: no formula of railcontact divides by 1 - 2 nu, and Kalker's table
// has a column for it.
void validate(const Material& material);

// The physical range of a normal force F3 of one contact (N): from a laboratory twin-disc rig
// (tens to hundreds of N) to a heavy-haul wheel load (about 200 kN static) under the largest
// dynamic factors (wheel flats, rail joints: up to about 5), with a factor 10 to spare. Beyond
// 1e7 N steel yields long before (p0 of several 10 GPa) and a wheel-rail patch outgrows the rail
// head; below 1 N the patch is micrometres wide. A value like 1e300 N is a typing error, not a load.
inline constexpr double kMinimumNormalForce_N = 1.0;
inline constexpr double kMaximumNormalForce_N = 1e7;

// Throws railcontact::Error (invalid_input) unless normal_force_N lies in [kMinimumNormalForce_N,
// kMaximumNormalForce_N]; the message starts with `what`, says what is wrong and gives the value
// and the range: "hertz: the normal force F3 is too large (1e+300 N; allowed [1, 1e+07] N)".
void validate_normal_force(double normal_force_N, std::string_view what);

}  // namespace railcontact

// Rigid creepages of steady rolling (METHOD.md §2): xi, eta dimensionless, spin phi in 1/m.
// Forces follow Kalker's sign convention: F1 = -G c^2 C11 xi, etc.

namespace railcontact {

struct Creepage {
  double xi = 0.0;    // longitudinal creepage (-)
  double eta = 0.0;   // lateral creepage (-)
  double phi = 0.0;   // spin creepage (1/m)
};

// The creepages of each strip of a patch (mesh column i2: the elements at one x2), for a conformal
// patch whose strips lie in frames of their own (docs/WHEELSET.md §4 "Conformal contact"): the
// rigid slip of an element of strip i2 at x1 (from the patch's origin) is (xi, eta + phi x1) of
// creepages[i2]. One creepage (xi, eta, phi) for the whole patch is the special case
// (xi − phi x2(i2), eta, phi).
using StripCreepages = std::vector<Creepage>;

// The range of the creepages of one contact. |xi|, |eta| <= 0.5: a wheel sliding at half the
// rolling speed (a locked or spinning wheel is 1); the traction saturates at mu p3 from about
// 3 mu F3 / (G c^2 C11), a few 1e-3 for wheel-rail patches, so 0.5 is a hundred times past the
// saturation, and beyond it the steady-rolling model no longer describes the contact. |phi| <= 100
// 1/m: the spin of a contact angle of 90 degrees on a wheel of radius 10 mm (phi = sin(gamma) / r),
// far beyond a flange contact on a railway wheel (sin(70 deg) / 0.46 m = 2 1/m).
inline constexpr double kMaximumCreepage = 0.5;
inline constexpr double kMaximumSpinCreepage_per_m = 100.0;

// Throws railcontact::Error (invalid_input) unless xi, eta and phi are finite, |xi|, |eta| <=
// kMaximumCreepage and |phi| <= kMaximumSpinCreepage_per_m. The message names the value as
// `structure`.xi, .eta and .`spin_field` (how the caller gave them): "rc_creepage.xi = 1e+200 must
// lie in [-0.5, 0.5] (…)".
void validate_creepage(const Creepage& creepage, std::string_view structure, std::string_view spin_field = "phi");

// Tangential force and spin moment on the wheel (upper body), in the contact frame.
struct TangentialForces {
  double F1_N = 0.0;   // longitudinal force
  double F2_N = 0.0;   // lateral force
  double M3_Nm = 0.0;  // spin moment about X3 through the pressure centre
};

}  // namespace railcontact

// The regular mesh of the potential contact area (METHOD.md §3) and the set of elements in
// contact on it. Element (i1, i2) has its centre at
//   x1 = x1_first + i1 * dx1,  x2 = x2_first + i2 * dx2,
// and is stored at index i2 * n1 + i1: a strip (fixed x2, all x1) is contiguous, and x1 grows
// towards the leading edge (rolling direction +X1).

namespace railcontact {

struct Mesh {
  int n1 = 0;             // elements along X1 (rolling direction)
  int n2 = 0;             // elements along X2 (lateral)
  double dx1_m = 0.0;     // element length along X1
  double dx2_m = 0.0;     // element width along X2
  double x1_first_m = 0.0;  // centre of the first element column
  double x2_first_m = 0.0;  // centre of the first element row

  [[nodiscard]] std::size_t size() const { return static_cast<std::size_t>(n1) * static_cast<std::size_t>(n2); }
  [[nodiscard]] std::size_t index(int i1, int i2) const {
    return static_cast<std::size_t>(i2) * static_cast<std::size_t>(n1) + static_cast<std::size_t>(i1);
  }
  [[nodiscard]] double x1(int i1) const { return x1_first_m + i1 * dx1_m; }
  [[nodiscard]] double x2(int i2) const { return x2_first_m + i2 * dx2_m; }
  [[nodiscard]] double element_area_m2() const { return dx1_m * dx2_m; }

  // Mesh of n1 x n2 elements exactly covering [x1_min, x1_max] x [x2_min, x2_max].
  static Mesh covering(double x1_min, double x1_max, double x2_min, double x2_max, int n1, int n2);
};

// Throws railcontact::Error unless the mesh has positive size and element lengths, and fits
// the memory budget of the solvers (at most max_elements elements).
void validate(const Mesh& mesh, std::size_t max_elements = 16u << 20);

// Elements in contact on a mesh: a flag per mesh element and the list of their indices in
// increasing order (strip by strip, each strip from trailing to leading edge).
class ContactElements {
 public:
  ContactElements() = default;
  ContactElements(const Mesh& mesh, std::vector<std::uint8_t> in_contact);

  [[nodiscard]] const Mesh& mesh() const { return mesh_; }
  [[nodiscard]] std::size_t count() const { return active_.size(); }
  [[nodiscard]] bool in_contact(std::size_t mesh_index) const { return flags_[mesh_index] != 0; }
  [[nodiscard]] const std::vector<std::uint8_t>& flags() const { return flags_; }
  // Mesh indices of the elements in contact.
  [[nodiscard]] const std::vector<std::size_t>& indices() const { return active_; }

 private:
  Mesh mesh_;
  std::vector<std::uint8_t> flags_;
  std::vector<std::size_t> active_;
};

}  // namespace railcontact

// The contact patch shared by every tangential solver (FastSim, nH-FastSim, the adhesion and
// exact steady-rolling solvers): the mesh of the potential contact area, the elements in
// contact, the normal pressure p3 on them, the material, and the strip structure.
//
// Frame (METHOD.md §2): X1 rolling direction (leading edge at the largest x1), X2 lateral,
// X3 normal into the wheel; the origin is the centre of pressure, so the mesh coordinates of
// a patch are shifted to make sum(p3 x1) = sum(p3 x2) = 0.


namespace railcontact {

// One run of consecutive contact elements in one strip (row of the mesh at fixed x2). A strip
// may hold several runs when the patch is not convex along X1.
struct StripRun {
  int i2 = 0;                 // strip (row) index
  int i1_trailing = 0;        // first element of the run (smallest x1)
  int i1_leading = 0;         // last element of the run (largest x1), inclusive
  std::size_t first = 0;      // position of the trailing element in ContactElements::indices()
  double x1_trailing_m = 0;   // trailing edge: x1(i1_trailing) - dx1/2
  double x1_leading_m = 0;    // leading edge:  x1(i1_leading)  + dx1/2
  [[nodiscard]] int length() const { return i1_leading - i1_trailing + 1; }
};

class ContactPatch {
 public:
  ContactPatch() = default;
  // pressure_Pa: one value per mesh element; elements with p3 > 0 are in contact. The mesh is
  // re-centred on the centre of pressure. Throws railcontact::Error if no element carries
  // pressure or a value is negative or not finite.
  ContactPatch(const Mesh& mesh, const std::vector<double>& pressure_Pa, const Material& material);

  [[nodiscard]] const Mesh& mesh() const { return elements_.mesh(); }
  [[nodiscard]] const ContactElements& elements() const { return elements_; }
  [[nodiscard]] const Material& material() const { return material_; }
  // p3 on the elements in contact, in the order of elements().indices().
  [[nodiscard]] const std::vector<double>& pressure_Pa() const { return pressure_; }
  [[nodiscard]] const std::vector<StripRun>& runs() const { return runs_; }
  [[nodiscard]] double normal_force_N() const { return normal_force_N_; }
  [[nodiscard]] double area_m2() const { return static_cast<double>(elements_.count()) * mesh().element_area_m2(); }
  // Shift applied to the input mesh coordinates to put the origin at the centre of pressure.
  [[nodiscard]] double x1_shift_m() const { return x1_shift_m_; }
  [[nodiscard]] double x2_shift_m() const { return x2_shift_m_; }
  // Coordinates of contact element e (position in indices()).
  [[nodiscard]] double x1(std::size_t e) const { return mesh().x1(static_cast<int>(elements_.indices()[e] % mesh().n1)); }
  [[nodiscard]] double x2(std::size_t e) const { return mesh().x2(static_cast<int>(elements_.indices()[e] / mesh().n1)); }

 private:
  ContactElements elements_;
  Material material_;
  std::vector<double> pressure_;
  std::vector<StripRun> runs_;
  double normal_force_N_ = 0.0;
  double x1_shift_m_ = 0.0, x2_shift_m_ = 0.0;
};

// The blocks of fine elements that make one coarse element: `along` elements along x1 (the rolling
// direction) times `across` elements along x2, each in [1, kMaximumCoarsening + 1].
struct CoarseBlocks {
  int along = 1;
  int across = 1;
  bool operator==(const CoarseBlocks&) const = default;
};

// The patch on a coarser mesh: each block of blocks.along x blocks.across elements (counted from
// the mesh's first element) becomes one element, in contact when at least half of its elements
// are, carrying the block's normal force (so the load and, nearly, the centre of pressure are
// kept). The coarse mesh is cropped to the bounding box of its elements in contact (the FFTs of K2
// then cover the patch only). Used for cheaper nH-FastSim flexibilities: K2 and FastSim's adhesion
// terms depend only on the shape.
inline constexpr int kMaximumCoarsening = 8;
ContactPatch coarsened(const ContactPatch& patch, CoarseBlocks blocks);
// Square blocks of factor x factor elements, factor in [1, kMaximumCoarsening].
ContactPatch coarsened(const ContactPatch& patch, int factor);

// The physical range of an elliptical contact (docs/RELIABILITY.md "Values and solvers").
// Semi-axes a, b in [10 um, 100 mm]: from a micro-contact of a laboratory rig to beyond the rail
// head (about 70 mm wide: a wheel-rail patch is a few mm to 20 mm long). Below, a patch of 98 kN
// carried pressures of 1e16 Pa; above, no body of railcontact's scope is that large.
inline constexpr double kMinimumSemiAxis_m = 1e-5;
inline constexpr double kMaximumSemiAxis_m = 0.1;
// The axis ratio a/b of an ellipse in [0.01, 100] (Kalker's table covers 0.1 ... 10; beyond 100 the
// meshes of the solvers resolve the narrow direction with too few elements).
inline constexpr double kMinimumEllipseAxisRatio = 0.01;
inline constexpr double kMaximumEllipseAxisRatio = 100.0;
// The largest Hertzian maximum pressure p0 = 3 F3 / (2 pi a b): 100 GPa, 50 times a heavy-haul
// wheel-rail contact (about 2 GPa) and beyond the strength of any solid; linear elasticity (the
// half-space theory of every solver) has long ceased to hold there.
inline constexpr double kMaximumHertzPressure_Pa = 1e11;

// Throws Error (invalid_input) unless value lies in [kMinimumSemiAxis_m, kMaximumSemiAxis_m];
// `name` is the input as the caller gave it ("rc_patch.a_m", "[geometry] a").
void validate_semi_axis(double value_m, std::string_view name);
// Throws Error (invalid_input) unless the ellipse a x b carrying F3 has an axis ratio in
// [kMinimumEllipseAxisRatio, kMaximumEllipseAxisRatio] and p0 <= kMaximumHertzPressure_Pa;
// `inputs` names what gave the ellipse ("the semi-axes a = 1e-05 m, b = 1e-05 m").
void validate_ellipse(double a_m, double b_m, double normal_force_N, std::string_view inputs);

// Hertzian pressure p0 sqrt(1 - (x1/a)^2 - (x2/b)^2) on an elliptical patch (elements whose
// centre lies inside the ellipse), scaled so that the discrete normal force equals F3. Throws
// Error unless a, b lie in [kMinimumSemiAxis_m, kMaximumSemiAxis_m], F3 in [kMinimumNormalForce_N,
// kMaximumNormalForce_N] and the ellipse passes validate_ellipse.
ContactPatch hertzian_patch(const ContactElements& ellipse, double a_m, double b_m, double normal_force_N,
                            const Material& material);

}  // namespace railcontact

// An elliptical contact patch on a regular mesh: the mesh covers the bounding rectangle
// [-a, a] x [-b, b] and the elements whose centre lies inside the ellipse are in contact
// (paper §3).

namespace railcontact {

// How the bounding box is divided.
enum class EllipseMeshLayout {
  // n x n elements whatever a/b (the paper's meshes): elements are a/b times longer along X1
  // than across, coarse along the rolling direction when a > b.
  equal_counts,
  // dx1 = dx2 min(1, a/b): square elements when a >= b, the paper's layout when a < b, so the
  // rolling direction is never resolved more coarsely than the lateral one.
  rolling_resolved,
};

// Mesh with n1 x n2 elements over the bounding box.
ContactElements elliptical_contact(double a_m, double b_m, int n1, int n2);
// Mesh with n x n elements over the bounding box.
ContactElements elliptical_contact(double a_m, double b_m, int elements_per_axis);

// About target_elements inside the ellipse (pi/4 of the mesh), with the given layout.
ContactElements elliptical_contact_with_count(double a_m, double b_m, int target_elements,
                                              EllipseMeshLayout layout = EllipseMeshLayout::equal_counts);

}  // namespace railcontact
