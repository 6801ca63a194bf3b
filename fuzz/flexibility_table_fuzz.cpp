// Fuzz target: flexibility-table files (JSON, src/flexibility_table/flexibility_table_file.cpp):
// the JSON parse, format and version, every key of the metadata, grids, contact jumps and nodes,
// the table's own checks (grids, node values), then what `railcontact run --flextable` does with
// it: the material, recipe and contact-reference checks and lookups between and at the grid points.
#include <algorithm>
#include <string>

#include "fuzz_target.hpp"
#include "railcontact/flexibility_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (256u << 20)) return 0;  // load_flexibility_table refuses larger files before parsing
  railcontact::fuzz::expect_clean_outcome([&] {
    const railcontact::FlexibilityTable table =
        railcontact::parse_flexibility_table(std::string(railcontact::fuzz::as_text(data, size)), "fuzz.json");
    railcontact::fuzz::expect_clean_outcome([&] { table.check_material(railcontact::Material{}, 0.0); });
    railcontact::fuzz::expect_clean_outcome([&] { table.check_recipe(0, 0.0); });
    railcontact::fuzz::expect_clean_outcome(
        [&] { table.check_contact_reference(railcontact::ContactReference::smooth); });
    const auto& y = table.y_m();
    const auto& loads = table.vertical_loads_N();
    const std::size_t ny = std::min<std::size_t>(y.size(), 64), nl = std::min<std::size_t>(loads.size(), 8);
    for (std::size_t iy = 0; iy < ny; ++iy) {
      for (std::size_t il = 0; il < nl; ++il) {
        const double y_mid = iy + 1 < y.size() ? 0.5 * (y[iy] + y[iy + 1]) : y[iy];
        const double load_mid = il + 1 < loads.size() ? 0.5 * (loads[il] + loads[il + 1]) : loads[il];
        railcontact::fuzz::expect_clean_outcome([&] { (void)table.lookup(y[iy], loads[il]); });
        railcontact::fuzz::expect_clean_outcome([&] { (void)table.lookup(y_mid, load_mid); });
        railcontact::fuzz::expect_clean_outcome([&] { (void)table.lookup_for_patch(y_mid, load_mid, 1e-4); });
      }
    }
  });
  return 0;
}
