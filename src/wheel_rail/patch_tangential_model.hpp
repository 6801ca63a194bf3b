#pragma once
// The tangential model the wheelset runs on one of its patches, planar or conformal
// (railcontact/tangential_model.hpp): the wheelset's nH-FastSim recipe and exact-solver options,
// per lobe on a patch of several, the patch's equivalent ellipse for FastSim and the small-patch
// fallback.
#include "railcontact/tangential_model.hpp"
#include "railcontact/wheelset.hpp"

namespace railcontact::detail {

inline TangentialModel patch_tangential_model(TangentialSolver solver, const ContactPatch& patch,
                                              const WheelsetOptions& options) {
  TangentialModelOptions model;
  model.solver = solver;
  model.nh_fastsim = options.nh_fastsim;
  model.rolling = options.rolling;
  return TangentialModel(patch, model);
}

}  // namespace railcontact::detail
