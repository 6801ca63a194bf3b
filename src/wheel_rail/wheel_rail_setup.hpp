#pragma once
// Internal: the wheel–rail set-up reader from a file's text (read_wheel_rail_setup = read_text_file,
// then parse_wheel_rail_setup); used by the fuzz targets (fuzz/).
#include <filesystem>
#include <string_view>

#include "railcontact/wheel_rail.hpp"

namespace railcontact::wheel_rail {

// `path` names the file in messages; relative profile paths are resolved against its directory.
// The same checks and errors as read_wheel_rail_setup.
WheelRailSetup parse_wheel_rail_setup(std::string_view content, const std::filesystem::path& path);

}  // namespace railcontact::wheel_rail
