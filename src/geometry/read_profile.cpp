// Dispatch of read_profile on the file extension, and the small profile transformations.
#include <fmt/core.h>

#include <cmath>

#include "geometry/profile_text.hpp"
#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {

Profile read_profile(const std::filesystem::path& path, const ProfileReadOptions& options) {
  const std::string extension = geometry::lower_case(path.extension().string());
  Profile profile;
  if (extension == ".prw" || extension == ".prr") {
    profile = read_simpack_profile(path);
  } else if (extension == ".ban" || extension == ".whl") {
    profile = read_miniprof_profile(path, options.miniprof_auto_vertical);
  } else {
    profile = read_text_profile(path, options.text_length_unit_m);
  }
  if (options.mirror_y) profile = mirrored_y(std::move(profile));
  if (options.mirror_z) profile = mirrored_z(std::move(profile));
  profile = curated(std::move(profile), options.role, options.curation);
  validate(profile);
  return profile;
}

Profile mirrored_y(Profile profile) {
  for (auto& v : profile.y_m) v = -v;
  return profile;
}

Profile mirrored_z(Profile profile) {
  for (auto& v : profile.z_m) v = -v;
  return profile;
}

void validate(const Profile& profile) {
  geometry::check_profile(profile,
                          "check the length unit: SIMPACK units.len.f is file units per metre (1000: millimetres), "
                          "MiniProf and plain-text profiles are read as millimetres");
}

}  // namespace railcontact
