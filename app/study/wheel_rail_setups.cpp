#include "study/wheel_rail_setups.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact::study {

std::vector<std::filesystem::path> wheel_rail_setup_files(const std::vector<std::filesystem::path>& given) {
  if (!given.empty()) return given;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(default_wheel_rail_setup_path().parent_path()))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

WheelsetTrack wheelset_track_of(const WheelRailSetup& setup) {
  return WheelsetTrack(read_profile(setup.wheel_profile, ProfileReadOptions{.role = ProfileKind::wheel}),
                       read_profile(setup.rail_profile, ProfileReadOptions{.role = ProfileKind::rail}), setup.track);
}

void validate_sweep(double element_size_m, double y_step_m, double largest_y_step_m, const std::vector<double>& yaws_rad) {
  require(std::isfinite(element_size_m) && element_size_m >= 0.05e-3 && element_size_m <= 2e-3, [&] {
    return fmt::format("--element-size-m {:g} m must lie in [5e-05, 0.002] m", element_size_m);
  });
  require(std::isfinite(y_step_m) && y_step_m >= 0.01e-3 && y_step_m <= largest_y_step_m, [&] {
    return fmt::format("--y-step-m {:g} m must lie in [1e-05, {:g}] m", y_step_m, largest_y_step_m);
  });
  require(!yaws_rad.empty() && yaws_rad.size() <= 10, "--yaw-rad: 1 to 10 yaw angles");
  for (const double yaw : yaws_rad)
    require(std::isfinite(yaw) && std::abs(yaw) <= 0.05,
            [&] { return fmt::format("--yaw-rad {:g} rad must lie in [-0.05, 0.05] rad", yaw); });
}

}  // namespace railcontact::study
