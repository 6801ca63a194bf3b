// Fuzz target: wheelset-table files (JSON, src/wheelset_table/wheelset_table_file.cpp): the
// JSON parse, format and version, the metadata, grids and every node and patch (runtime meshes and
// pressures included), the table's own checks, then what `railcontact wheelset --table` does with
// it: lookups at and between the grid points, with yaw.
#include <algorithm>
#include <string>

#include "fuzz_target.hpp"
#include "railcontact/wheelset_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (512u << 20)) return 0;  // load_wheelset_table refuses larger files before parsing
  railcontact::fuzz::expect_clean_outcome([&] {
    const railcontact::WheelsetTable table =
        railcontact::parse_wheelset_table(std::string(railcontact::fuzz::as_text(data, size)), "fuzz.json");
    const railcontact::WheelsetTableGrid& grid = table.grid();
    const std::size_t ny = std::min<std::size_t>(grid.y_m.size(), 16), nl = std::min<std::size_t>(grid.wheel_load_N.size(), 4);
    for (std::size_t iy = 0; iy < ny; ++iy) {
      for (std::size_t il = 0; il < nl; ++il) {
        railcontact::WheelsetState state;
        state.position.lateral_displacement_m =
            iy + 1 < grid.y_m.size() ? 0.5 * (grid.y_m[iy] + grid.y_m[iy + 1]) : grid.y_m[iy];
        state.position.yaw_rad = grid.yaw_rad.front();
        const double load = grid.wheel_load_N[il];
        railcontact::fuzz::expect_clean_outcome(
            [&] { (void)table.evaluate(state, railcontact::WheelLoads{load, load, false}, 0.3); });
        state.position.yaw_rad = 0.5 * (grid.yaw_rad.front() + grid.yaw_rad.back());
        railcontact::fuzz::expect_clean_outcome(
            [&] { (void)table.evaluate(state, railcontact::WheelLoads{load, load, false}, 0.3); });
      }
    }
  });
  return 0;
}
