#include "study/patch_files.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cerrno>
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

}  // namespace railcontact::study
