#pragma once
// railcontact: wheel–rail rolling contact with nH-FastSim and its exact reference solvers.
// The whole public API, one header per pipeline stage (docs/ARCHITECTURE.md):
//   error.hpp             Error and its kinds
//   text_file.hpp         bounded, checked reading of input files
//   contact_patch.hpp     material, creepages, forces, mesh, contact patch (docs/METHOD.md §2-3)
//   hertz.hpp             Hertz's solution (the normal problem of an ellipse)
//   kalker.hpp            Kalker's linear theory: C11, C22, C23, FastSim's flexibilities (Eq 9)
//   geometry.hpp          profiles, the wheel–rail pair, contact point, undeformed distance
//   contact_geometry.hpp  the rigid wheelset on its track: Δr(y), contact angles, roll, equivalent conicity
//   normal.hpp            the non-Hertzian normal problem (docs/METHOD.md §5)
//   tangential.hpp        K2 (Eq 10-18), FastSim (Eq 1-9), NhFastSim (Eq 19-21), exact rolling (Eq A1)
//   wheel_rail.hpp        the wheel–rail stage: profiles in, contact patch with angle, spin, F3 out
//   wheelset_geometry.hpp the wheelset on its track in 3-D: contact search, regions, tangent planes
//   wheelset_kinematics.hpp the wheelset's motion and the kinematic creepages of a contact
//   wheelset.hpp          the wheelset evaluated as a whole: options, patches, Wheelset
//   flexibility_table.hpp precomputed nH-FastSim flexibilities over y and load
//   wheelset_table.hpp    the wheelset precomputed over y, yaw and load
// Units are SI throughout (m, N, Pa, rad; spin in 1/m); names carry the unit where it matters.
#include "railcontact/contact_geometry.hpp"
#include "railcontact/contact_patch.hpp"
#include "railcontact/error.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/normal.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/tangential_model.hpp"
#include "railcontact/text_file.hpp"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset.hpp"
#include "railcontact/wheelset_geometry.hpp"
#include "railcontact/wheelset_kinematics.hpp"
#include "railcontact/wheelset_table.hpp"
