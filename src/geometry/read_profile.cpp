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
  const std::string name = profile.source.empty() ? std::string("(unnamed)") : profile.source;
  require(profile.y_m.size() == profile.z_m.size(), [&] {
    return fmt::format("profile {}: {} y values but {} z values", name, profile.y_m.size(), profile.z_m.size());
  });
  require(profile.size() >= 4,
          [&] { return fmt::format("profile {}: {} points; at least 4 are needed", name, profile.size()); });
  for (std::size_t i = 0; i < profile.size(); ++i) {
    require(std::isfinite(profile.y_m[i]) && std::isfinite(profile.z_m[i]),
            [&] { return fmt::format("profile {}: point {} is not finite", name, i + 1); });
  }
}

}  // namespace railcontact
