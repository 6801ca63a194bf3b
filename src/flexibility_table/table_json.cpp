// Profile fingerprints and track parameters in the table files (table_json.hpp).
#include "flexibility_table/table_json.hpp"

#include <fmt/format.h>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"
#include "support/file_fingerprint.hpp"

namespace railcontact::detail {

using nlohmann::json;

FileFingerprint read_fingerprint(StrictJsonReader& parent, const std::string& key) {
  StrictJsonReader r = parent.child(key);
  FileFingerprint f;
  f.file = r.string("file");
  const std::string hex = r.string("fnv1a64");
  try {
    f.fnv1a64 = parse_fnv1a64_hex(hex);
  } catch (const Error&) {
    r.fail(fmt::format("{} = \"{}\" is not a 64-bit FNV-1a hash (16 hexadecimal digits)", r.qualified("fnv1a64"),
                       printable_excerpt(hex)));
  }
  r.finish();
  return f;
}

json fingerprint_json(const FileFingerprint& fingerprint) {
  return {{"file", fingerprint.file}, {"fnv1a64", fnv1a64_hex(fingerprint.fnv1a64)}};
}

TrackWheelsetParameters read_track_parameters(StrictJsonReader& parent, const std::string& key) {
  const nlohmann::json& object = parent.get(key);
  const bool has_datum = object.is_object() && object.contains("nominal_radius_at");
  const bool has_cant = object.is_object() && object.contains("rail_cant_rad");
  StrictJsonReader t = parent.child(key);
  TrackWheelsetParameters track;
  track.track_gauge_m = t.number("track_gauge_m");
  track.gauge_measuring_depth_m = t.number("gauge_measuring_depth_m");
  track.flange_back_distance_m = t.number("flange_back_distance_m");
  track.flange_back_y_m = t.number("flange_back_y_m");
  track.taping_line_from_flange_back_m = t.number("taping_line_from_flange_back_m");
  track.nominal_rolling_radius_m = t.number("nominal_rolling_radius_m");
  // A file without the datum of r0 was written when r0 was measured at the taping line.
  track.nominal_radius_at = NominalRadiusDatum::taping_line;
  if (has_datum) {
    try {
      track.nominal_radius_at = parse_nominal_radius_datum(t.string("nominal_radius_at"));
    } catch (const Error& e) {
      t.fail(e.what());
    }
  }
  // A file without the rail cant was built on the rail profile as given (cant 0).
  if (has_cant) track.rail_cant_rad = t.number("rail_cant_rad");
  t.finish();
  return track;
}

json track_parameters_json(const TrackWheelsetParameters& t) {
  json j = {{"track_gauge_m", t.track_gauge_m},
            {"gauge_measuring_depth_m", t.gauge_measuring_depth_m},
            {"flange_back_distance_m", t.flange_back_distance_m},
            {"flange_back_y_m", t.flange_back_y_m},
            {"taping_line_from_flange_back_m", t.taping_line_from_flange_back_m},
            {"nominal_rolling_radius_m", t.nominal_rolling_radius_m},
            {"nominal_radius_at", nominal_radius_datum_name(t.nominal_radius_at)}};
  // Written only when non-zero: a table on an uncanted rail stays as it was and readable by
  // builds that do not know the key; one on a canted rail is refused by them (an unknown key).
  if (t.rail_cant_rad != 0.0) j["rail_cant_rad"] = t.rail_cant_rad;
  return j;
}

}  // namespace railcontact::detail
