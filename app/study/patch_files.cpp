#include "study/patch_files.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cerrno>
#include <algorithm>
#include <cmath>
#include <fstream>

#include "railcontact/error.hpp"
#include "output/output_directory.hpp"

namespace railcontact::study {

void write_pressure_csv(const std::filesystem::path& path, const ContactPatch& patch) {
  std::ofstream csv(path);
  if (!csv) throw output::write_error(path, errno);
  csv << "x1_m,x2_m,pressure_Pa\n";
  for (std::size_t e = 0; e < patch.elements().count(); ++e)
    fmt::print(csv, "{:.9e},{:.9e},{:.9e}\n", patch.x1(e), patch.x2(e), patch.pressure_Pa()[e]);
  csv.close();  // a full disk shows here
  if (!csv) throw output::write_error(path, errno);
}

nlohmann::json patch_json(const WheelRailPatch& p) {
  const WheelRailContactPoint& c = p.contact;
  const Mesh& mesh = p.potential_area;
  nlohmann::json hertz = nullptr;
  if (p.local_hertz.a_m > 0.0) {
    hertz = {{"a_m", p.local_hertz.a_m},
             {"b_m", p.local_hertz.b_m},
             {"area_m2", M_PI * p.local_hertz.a_m * p.local_hertz.b_m},
             {"max_pressure_Pa", p.local_hertz.max_pressure_Pa},
             {"approach_m", p.local_hertz.approach_m}};
  }
  nlohmann::json reference = nullptr;
  if (p.reference == ContactReference::smooth) {
    reference = {{"y_rail_m", p.region.rail_profile_y_m},
                 {"y_wheel_m", p.region.wheel_profile_y_m},
                 {"point_track_m", p.region.reference_point_track_m},
                 {"wheelset_vertical_displacement_m", p.vertical_displacement_m},
                 {"load_iterations", p.load_iterations}};
  }
  return {
      {"y", p.lateral_displacement_m},
      {"contact_reference", contact_reference_name(p.reference)},
      {"reference_point", reference},
      {"contact_angle_rad", p.contact_angle_rad},
      {"rolling_radius_m", p.rolling_radius_m},
      {"spin_per_m", p.spin_per_m},
      {"normal_force_N", p.normal_force_N},
      {"area_m2", p.area_m2},
      {"elements_in_contact", p.elements_in_contact},
      {"extent_x1_m", p.extent_x1_m},
      {"extent_x2_m", p.extent_x2_m},
      {"max_pressure_Pa", p.max_pressure_Pa},
      {"approach_m", p.approach_m},
      {"iterations", p.iterations},
      {"vertical_load_N", p.vertical_load_N},
      {"patches", p.patches},
      {"contact_point",
       {{"y_rail_m", c.y_rail_m},
        {"z_rail_m", c.z_rail_m},
        {"y_wheel_m", c.y_wheel_m},
        {"z_wheel_m", c.z_wheel_m},
        {"y_track_m", c.y_track_m},
        {"A_per_m", c.A_per_m},
        {"B_per_m", c.B_per_m}}},
      {"pressure_centre_x1_m", p.pressure_centre_x1_m},
      {"pressure_centre_x2_m", p.pressure_centre_x2_m},
      {"pressure_centre_y_rail_m", p.pressure_centre_y_rail_m},
      {"pressure_centre_contact_angle_rad", p.pressure_centre_contact_angle_rad},
      {"mesh",
       {{"n1", mesh.n1}, {"n2", mesh.n2}, {"dx1_m", mesh.dx1_m}, {"dx2_m", mesh.dx2_m}, {"passes", p.mesh_passes}}},
      {"local_hertz", hertz},
  };
}

nlohmann::json vector_json(const Vector3& v) { return nlohmann::json::array({v[0], v[1], v[2]}); }

nlohmann::json wheelset_patch_json(const WheelsetPatch& p) {
  nlohmann::json j = {
      {"reference_point_track_m", vector_json(p.region.reference_point_track_m)},
      {"rail_profile_y_m", p.region.rail_profile_y_m},
      {"wheel_profile_y_m", p.region.wheel_profile_y_m},
      {"contact_angle_rad", p.region.contact_angle_rad},
      {"creepage_point_track_m", vector_json(p.creepage_point_track_m)},
      {"approach_m", p.approach_m},
      {"rolling_radius_m", p.rolling_radius_m},
      {"rolling_speed_m_per_s", p.rolling_speed_m_per_s},
      {"x1_axis_track", vector_json(p.region.x1_axis)},
      {"x2_axis_track", vector_json(p.region.x2_axis)},
      {"x3_axis_track", vector_json(p.region.x3_axis)},
      {"max_interpenetration_m", p.region.max_interpenetration_m},
      {"area_m2", p.area_m2},
      {"max_pressure_Pa", p.max_pressure_Pa},
      {"elements_in_contact", p.elements_in_contact},
      {"normal_force_N", p.normal_force_N},
      {"creepage", {{"xi", p.creepage.xi}, {"eta", p.creepage.eta}, {"phi_per_m", p.creepage.phi}}},
      {"pressure_centre_from_reference_m", {p.pressure_centre_x1_m, p.pressure_centre_x2_m}},
      {"contact_surface", contact_surface_name(p.surface)},
      {"conformal_weight", p.conformal_weight},
      {"coupling_lift_m", p.coupling_lift_m},
      {"pressure_force_track_N", vector_json(p.pressure_force_track_N)},
  };
  // A conformal patch: the turn of its strips in contact from the contact frame (rad).
  if (!p.strips.empty()) {
    const auto [lowest, highest] = std::minmax_element(
        p.strips.begin(), p.strips.end(),
        [](const ConformalStrip& a, const ConformalStrip& b) { return a.angle_rad < b.angle_rad; });
    j["strip_angle_range_rad"] = {lowest->angle_rad, highest->angle_rad};
  }
  // The rail normal angle's range over the overlap and its largest difference from the contact
  // angle (absent for a patch from a wheelset table, which does not keep them).
  const double variation = contact_angle_variation_rad(p.region);
  if (std::isfinite(variation)) {
    j["contact_angle_range_rad"] = {p.region.contact_angle_min_rad, p.region.contact_angle_max_rad};
    j["contact_angle_variation_rad"] = variation;
    j["large_angle_variation"] = variation > kLargeContactAngleVariation_rad;
    j["contact_angle_spread_rad"] = p.region.contact_angle_spread_rad;
  }
  for (const PatchSolverResult& s : p.solvers) {
    j[solver_name(s.solver)] = {{"F1_N", s.forces.F1_N},
                                {"F2_N", s.forces.F2_N},
                                {"M3_Nm", s.forces.M3_Nm},
                                {"force_track_N", vector_json(s.force_track_N)}};
  }
  return j;
}

}  // namespace railcontact::study
