// The C API's wheelset (include/railcontact/railcontact.h, docs/C_API.md "Wheelset"): exactly the
// numbers of the C++ Wheelset, the mirror symmetry of the two wheels, the batch and two handles on
// two threads equal to the serial loop, statuses and messages for bad input; and the single-patch
// normal problem with the approach given (rc_solver_set_patch_at_approach).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "railcontact/hertz.hpp"
#include "railcontact/normal.hpp"
#include "railcontact/railcontact.h"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset.hpp"
#include "railcontact/wheelset_table.hpp"

namespace railcontact {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// A wheelset handle on the default S1002 / UIC60 track, coarse elements (0.5 mm) for speed.
struct CWheelset {
  rc_wheelset* h = nullptr;
  explicit CWheelset(bool by_load = true, int warm_start = 1, std::vector<int> solvers = {RC_METHOD_NH_FASTSIM}) {
    EXPECT_EQ(rc_wheelset_create(&h), RC_OK);
    EXPECT_EQ(rc_wheelset_set_default_track(h), RC_OK) << error();
    rc_wheelset_options o;
    rc_wheelset_options_default(&o);
    o.element_size_m = 0.5e-3;
    o.normal_mode = by_load ? RC_WHEELSET_BY_LOAD : RC_WHEELSET_BY_POSITION;
    o.allow_wheel_lift = by_load ? 0 : 1;
    o.warm_start = warm_start;
    o.solver_count = static_cast<int>(solvers.size());
    for (std::size_t k = 0; k < solvers.size(); ++k) o.solvers[k] = solvers[k];
    EXPECT_EQ(rc_wheelset_set_options(h, &o), RC_OK) << error();
  }
  ~CWheelset() { rc_wheelset_destroy(h); }
  CWheelset(const CWheelset&) = delete;
  CWheelset& operator=(const CWheelset&) = delete;
  std::string error() const {
    std::size_t length = 0;
    rc_wheelset_last_error(h, nullptr, 0, &length);
    std::string message(length + 1, '\0');
    rc_wheelset_last_error(h, message.data(), message.size(), nullptr);
    message.resize(length);
    return message;
  }
  std::vector<rc_wheelset_patch> patches(int side) const {
    std::size_t n = 0;
    EXPECT_EQ(rc_wheelset_patch_count(h, side, &n), RC_OK);
    std::vector<rc_wheelset_patch> p(n);
    EXPECT_EQ(rc_wheelset_patches(h, side, n, p.data()), RC_OK);
    return p;
  }
};

// The C++ options the handle above stands for.
WheelsetOptions coarse(bool by_load, std::vector<TangentialSolver> solvers = {TangentialSolver::nh_fastsim}) {
  WheelsetOptions o;
  o.element_size_m = 0.5e-3;
  o.solvers = std::move(solvers);
  if (!by_load) {
    o.loads.reset();
    o.allow_wheel_lift = true;
  }
  return o;
}

rc_wheelset_state c_state(double y_m, double yaw_rad = 0.0, double z_m = 0.0) {
  rc_wheelset_state s;
  rc_wheelset_state_default(&s);
  s.y_m = y_m;
  s.yaw_rad = yaw_rad;
  s.z_m = z_m;
  s.lateral_velocity_m_per_s = 0.01;
  s.yaw_rate_rad_per_s = 0.02;
  return s;
}

WheelsetState cpp_state(const rc_wheelset_state& c) {
  WheelsetState s;
  s.position = WheelsetPosition{c.y_m, c.z_m, c.roll_rad, c.yaw_rad};
  s.velocity.forward_speed_m_per_s = c.forward_speed_m_per_s;
  s.velocity.lateral_velocity_m_per_s = c.lateral_velocity_m_per_s;
  s.velocity.yaw_rate_rad_per_s = c.yaw_rate_rad_per_s;
  s.velocity.extra_longitudinal_creepage = c.extra_longitudinal_creepage;
  return s;
}

const WheelsetTrack& track() {
  static const WheelsetTrack t = default_wheelset_track();
  return t;
}

void expect_same(const rc_wheelset_result& a, const rc_wheelset_result& b) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.force_track_N[i], b.force_track_N[i]);
    for (int w = 0; w < 2; ++w) EXPECT_EQ(a.wheel_force_track_N[w][i], b.wheel_force_track_N[w][i]);
  }
  for (int w = 0; w < 2; ++w) {
    EXPECT_EQ(a.wheel_vertical_displacement_m[w], b.wheel_vertical_displacement_m[w]);
    EXPECT_EQ(a.patch_count[w], b.patch_count[w]);
    EXPECT_EQ(a.load_iterations[w], b.load_iterations[w]);
  }
  EXPECT_EQ(a.vertical_displacement_m, b.vertical_displacement_m);
  EXPECT_EQ(a.roll_rad, b.roll_rad);
}

void expect_same(const rc_wheelset_patch& a, const rc_wheelset_patch& b) {
  EXPECT_EQ(a.side, b.side);
  EXPECT_EQ(a.normal_force_N, b.normal_force_N);
  EXPECT_EQ(a.contact_angle_rad, b.contact_angle_rad);
  EXPECT_EQ(a.creepage.xi, b.creepage.xi);
  EXPECT_EQ(a.creepage.phi_per_m, b.creepage.phi_per_m);
  EXPECT_EQ(a.elements_in_contact, b.elements_in_contact);
  for (int s = 0; s < 4; ++s) {
    EXPECT_EQ(a.forces[s].F1_N, b.forces[s].F1_N);
    EXPECT_EQ(a.forces[s].F2_N, b.forces[s].F2_N);
    EXPECT_EQ(a.forces[s].M3_Nm, b.forces[s].M3_Nm);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(a.force_track_N[s][i], b.force_track_N[s][i]);
  }
}

// The C API is a thin layer: the same numbers as railcontact::Wheelset, field by field, over a
// sequence of states (the warm start of both carried along), by load and by position.
TEST(CApiWheelset, EqualsTheCppWheelset) {
  for (const bool by_load : {true, false}) {
    CWheelset c(by_load, 1, {RC_METHOD_NH_FASTSIM, RC_METHOD_FASTSIM});
    Wheelset cpp(track(), coarse(by_load, {TangentialSolver::nh_fastsim, TangentialSolver::fastsim}));
    double nominal = 0.0;
    ASSERT_EQ(rc_wheelset_get_track(c.h, nullptr, &nominal), RC_OK);
    EXPECT_EQ(nominal, track().nominal_axle_height_m());
    for (const double y : {3e-3, 3.001e-3, -6.8e-3}) {
      // By position: 50 µm below the first touch (the other wheel may be lifted).
      const WheelsetPosition at{y, 0.0, 0.0, 1e-3};
      const double touching = std::max(track().touching_vertical_displacement_m(WheelSide::right, at),
                                       track().touching_vertical_displacement_m(WheelSide::left, at));
      const rc_wheelset_state s = c_state(y, 1e-3, touching - 50e-6);
      rc_wheelset_result r;
      ASSERT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_OK) << c.error();
      const WheelsetResult e = cpp.evaluate(cpp_state(s));
      for (int i = 0; i < 3; ++i) EXPECT_EQ(r.force_track_N[i], e.force_track_N[i]);
      EXPECT_EQ(r.vertical_displacement_m, e.state.position.vertical_displacement_m);
      EXPECT_EQ(r.roll_rad, e.state.position.roll_rad);
      for (int w = 0; w < 2; ++w) {
        const WheelResult& ew = e.wheels[w];
        EXPECT_EQ(r.wheel_vertical_displacement_m[w], ew.vertical_displacement_m);
        for (int i = 0; i < 3; ++i) EXPECT_EQ(r.wheel_force_track_N[w][i], ew.force_track_N[i]);
        const std::vector<rc_wheelset_patch> ps = c.patches(w);
        ASSERT_EQ(ps.size(), ew.patches.size());
        ASSERT_EQ(r.patch_count[w], static_cast<int>(ps.size()));
        for (std::size_t j = 0; j < ps.size(); ++j) {
          const rc_wheelset_patch& p = ps[j];
          const WheelsetPatch& q = ew.patches[j];
          EXPECT_EQ(p.side, w);
          for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(p.reference_point_track_m[i], q.region.reference_point_track_m[i]);
            EXPECT_EQ(p.x2_axis[i], q.region.x2_axis[i]);
            EXPECT_EQ(p.x3_axis[i], q.region.x3_axis[i]);
          }
          EXPECT_EQ(p.contact_angle_rad, q.region.contact_angle_rad);
          EXPECT_EQ(p.rolling_radius_m, q.rolling_radius_m);
          EXPECT_EQ(p.creepage.xi, q.creepage.xi);
          EXPECT_EQ(p.creepage.eta, q.creepage.eta);
          EXPECT_EQ(p.creepage.phi_per_m, q.creepage.phi);
          EXPECT_EQ(p.normal_force_N, q.normal_force_N);
          EXPECT_EQ(p.area_m2, q.area_m2);
          EXPECT_EQ(p.max_pressure_Pa, q.max_pressure_Pa);
          EXPECT_EQ(p.elements_in_contact, static_cast<int>(q.elements_in_contact));
          ASSERT_EQ(p.solver_count, 2);
          for (int k = 0; k < 2; ++k) {
            EXPECT_EQ(p.forces[k].F1_N, q.solvers[k].forces.F1_N);
            EXPECT_EQ(p.forces[k].F2_N, q.solvers[k].forces.F2_N);
            EXPECT_EQ(p.forces[k].M3_Nm, q.solvers[k].forces.M3_Nm);
            for (int i = 0; i < 3; ++i) EXPECT_EQ(p.force_track_N[k][i], q.solvers[k].force_track_N[i]);
          }
          EXPECT_EQ(p.forces[2].F1_N, 0.0);  // unused entries
        }
      }
      if (!by_load) EXPECT_GT(r.force_track_N[2], 0.0);
    }
  }
}

// The profile files of the shipped set-up, given one for both sides or one per wheel and rail
// with the set-up's dimensions, make the same wheelset as the default track.
// rc_wheelset_reset_warm_start: the next evaluation gives a fresh handle's numbers to the last digit.
TEST(CApiWheelset, ResetWarmStartGivesAFreshHandlesNumbers) {
  CWheelset used(false), fresh(false);
  rc_wheelset_result r{}, reset{}, first{};
  const rc_wheelset_state a = c_state(0.0, 0.0, -0.02e-3);
  ASSERT_EQ(rc_wheelset_evaluate(used.h, &a, &r), RC_OK) << used.error();
  const rc_wheelset_state b = c_state(0.3e-3, 1e-3, -0.02e-3);
  ASSERT_EQ(rc_wheelset_evaluate(used.h, &b, &r), RC_OK) << used.error();
  EXPECT_EQ(rc_wheelset_reset_warm_start(used.h), RC_OK);
  rc_wheelset_result kept{};
  EXPECT_EQ(rc_wheelset_result_get(used.h, &kept), RC_OK);  // the last result stays readable
  expect_same(kept, r);
  ASSERT_EQ(rc_wheelset_evaluate(used.h, &b, &reset), RC_OK) << used.error();
  ASSERT_EQ(rc_wheelset_evaluate(fresh.h, &b, &first), RC_OK) << fresh.error();
  expect_same(reset, first);
  for (int side = 0; side < 2; ++side) {
    const auto p = used.patches(side), q = fresh.patches(side);
    ASSERT_EQ(p.size(), q.size());
    for (std::size_t j = 0; j < p.size(); ++j) {
      expect_same(p[j], q[j]);
      EXPECT_EQ(p[j].normal_iterations, q[j].normal_iterations);
    }
  }
  EXPECT_EQ(rc_wheelset_reset_warm_start(nullptr), RC_INVALID_INPUT);
}

// rc_wheelset_time_stages: the stage times of the evaluations since it was switched on, summed
// over them also where each evaluation starts cold (warm_start = 0: a new C++ Wheelset each
// time), within the time measured around the calls; the numbers those of an untimed handle; off
// by default; switching zeroes them; a null handle or output refused.
TEST(CApiWheelset, StageTimesAddUpOverTheEvaluations) {
  for (const int warm_start : {1, 0}) {
    CWheelset timed(true, warm_start), plain(true, warm_start);
    rc_wheelset_stage_times t{};
    ASSERT_EQ(rc_wheelset_stage_times_get(timed.h, &t), RC_OK);
    EXPECT_EQ(t.evaluations, 0);
    ASSERT_EQ(rc_wheelset_time_stages(timed.h, 1), RC_OK);
    double wall_s = 0.0;
    for (int k = 0; k < 3; ++k) {
      const rc_wheelset_state s = c_state(1e-6 * k);
      rc_wheelset_result a{}, b{};
      const auto start = std::chrono::steady_clock::now();
      ASSERT_EQ(rc_wheelset_evaluate(timed.h, &s, &a), RC_OK) << timed.error();
      wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ASSERT_EQ(rc_wheelset_evaluate(plain.h, &s, &b), RC_OK) << plain.error();
      expect_same(a, b);
    }
    ASSERT_EQ(rc_wheelset_stage_times_get(timed.h, &t), RC_OK);
    EXPECT_EQ(t.evaluations, 3) << "warm_start " << warm_start;
    const double total_s =
        t.search_s + t.area_s + t.normal_s + t.height_s + t.kinematics_s + t.tangential_s + t.assembly_s;
    for (const double stage_s : {t.search_s, t.area_s, t.normal_s, t.height_s, t.tangential_s})
      EXPECT_GT(stage_s, 0.0) << "warm_start " << warm_start;
    EXPECT_LE(total_s, wall_s);
    EXPECT_GE(total_s, 0.9 * wall_s);
    ASSERT_EQ(rc_wheelset_stage_times_get(plain.h, &t), RC_OK);
    EXPECT_EQ(t.evaluations, 0);
    ASSERT_EQ(rc_wheelset_time_stages(timed.h, 0), RC_OK);
    ASSERT_EQ(rc_wheelset_stage_times_get(timed.h, &t), RC_OK);
    EXPECT_EQ(t.evaluations, 0);
    EXPECT_EQ(t.normal_s, 0.0);
  }
  rc_wheelset_stage_times t{};
  EXPECT_EQ(rc_wheelset_time_stages(nullptr, 1), RC_INVALID_INPUT);
  EXPECT_EQ(rc_wheelset_stage_times_get(nullptr, &t), RC_INVALID_INPUT);
  CWheelset c;
  EXPECT_EQ(rc_wheelset_stage_times_get(c.h, nullptr), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_stage_times_get: times"), std::string::npos) << c.error();
}

TEST(CApiWheelset, ProfileFilesGiveTheDefaultTrack) {
  CWheelset reference(true, 0);
  rc_track_parameters dimensions;
  ASSERT_EQ(rc_wheelset_get_track(reference.h, &dimensions, nullptr), RC_OK);
  const std::string wheel = default_wheel_profile_path().string(), rail = default_rail_profile_path().string();
  CWheelset two(true, 0), four(true, 0);
  ASSERT_EQ(rc_wheelset_set_track(two.h, wheel.c_str(), rail.c_str(), &dimensions), RC_OK) << two.error();
  ASSERT_EQ(rc_wheelset_set_track_profiles(four.h, wheel.c_str(), wheel.c_str(), rail.c_str(), rail.c_str(),
                                           &dimensions),
            RC_OK)
      << four.error();
  const rc_wheelset_state s = c_state(2e-3);
  rc_wheelset_result a, b, c;
  ASSERT_EQ(rc_wheelset_evaluate(reference.h, &s, &a), RC_OK) << reference.error();
  ASSERT_EQ(rc_wheelset_evaluate(two.h, &s, &b), RC_OK) << two.error();
  ASSERT_EQ(rc_wheelset_evaluate(four.h, &s, &c), RC_OK) << four.error();
  expect_same(a, b);
  expect_same(a, c);
}

// Forces with the wheelset at y are the mirror image of those at −y: wheel by wheel, Fx and Fz
// equal, Fy opposite (the right wheel at y is the left wheel at −y).
TEST(CApiWheelset, WheelsAtMinusYAreTheMirrorImageOfWheelsAtY) {
  CWheelset c(true, 0);
  for (const double y : {2.5e-3, -6.5e-3}) {
    rc_wheelset_state s = c_state(y, 1e-3);
    rc_wheelset_result a, b;
    ASSERT_EQ(rc_wheelset_evaluate(c.h, &s, &a), RC_OK) << c.error();
    s = c_state(-y, -1e-3);
    s.lateral_velocity_m_per_s = -s.lateral_velocity_m_per_s;
    s.yaw_rate_rad_per_s = -s.yaw_rate_rad_per_s;
    ASSERT_EQ(rc_wheelset_evaluate(c.h, &s, &b), RC_OK) << c.error();
    for (int w = 0; w < 2; ++w) {
      const double* f = a.wheel_force_track_N[w];
      const double* m = b.wheel_force_track_N[1 - w];
      const double scale = f[2];
      EXPECT_GT(scale, 9e4);
      EXPECT_NEAR(f[0], m[0], 1e-8 * scale);
      EXPECT_NEAR(f[1], -m[1], 1e-8 * scale);
      EXPECT_NEAR(f[2], m[2], 1e-8 * scale);
      EXPECT_EQ(a.patch_count[w], b.patch_count[1 - w]);
    }
    EXPECT_NEAR(a.force_track_N[1], -b.force_track_N[1], 1e-8 * a.force_track_N[2]);
    EXPECT_NEAR(a.roll_rad, -b.roll_rad, 1e-12);
  }
}

// The batch on three threads gives the numbers of the serial loop (cold evaluations) bit for bit,
// its patches included; too small a patch buffer is that state's RC_BUFFER_TOO_SMALL.
TEST(CApiWheelset, BatchOnThreadsEqualsTheSerialLoop) {
  CWheelset c(true, 0);
  std::vector<rc_wheelset_state> states;
  for (const double y : {-7e-3, -3e-3, 0.0, 2e-3, 5e-3}) states.push_back(c_state(y, 0.5e-3));
  const std::size_t n = states.size(), per_wheel = 3;
  std::vector<rc_wheelset_result> serial(n);
  std::vector<rc_wheelset_patch> serial_patches(2 * n * per_wheel);
  for (std::size_t k = 0; k < n; ++k) {
    ASSERT_EQ(rc_wheelset_evaluate(c.h, &states[k], &serial[k]), RC_OK) << c.error();
    for (int w = 0; w < 2; ++w) {
      const std::vector<rc_wheelset_patch> ps = c.patches(w);
      ASSERT_LE(ps.size(), per_wheel);
      std::copy(ps.begin(), ps.end(), serial_patches.begin() + static_cast<std::ptrdiff_t>((2 * k + w) * per_wheel));
    }
  }
  rc_wheelset_result last;
  ASSERT_EQ(rc_wheelset_result_get(c.h, &last), RC_OK);

  std::vector<rc_wheelset_result> batch(n);
  std::vector<rc_wheelset_patch> batch_patches(2 * n * per_wheel);
  std::vector<int> statuses(n, -1);
  ASSERT_EQ(rc_wheelset_batch_evaluate(c.h, n, states.data(), 3, batch.data(), per_wheel, batch_patches.data(),
                                       statuses.data()),
            RC_OK)
      << c.error();
  for (std::size_t k = 0; k < n; ++k) {
    EXPECT_EQ(statuses[k], RC_OK);
    expect_same(batch[k], serial[k]);
    for (int w = 0; w < 2; ++w)
      for (int j = 0; j < serial[k].patch_count[w]; ++j)
        expect_same(batch_patches[(2 * k + w) * per_wheel + j], serial_patches[(2 * k + w) * per_wheel + j]);
  }
  // The handle's own last result is unchanged.
  rc_wheelset_result after;
  ASSERT_EQ(rc_wheelset_result_get(c.h, &after), RC_OK);
  expect_same(after, last);

  // A failing state (NaN y) does not stop the others; no patch room for a wheel with patches.
  std::vector<rc_wheelset_state> two{states[2], states[3]};
  two[0].y_m = kNaN;
  std::vector<rc_wheelset_result> out(2);
  std::vector<int> st(2, -1);
  EXPECT_EQ(rc_wheelset_batch_evaluate(c.h, 2, two.data(), 2, out.data(), 0, nullptr, st.data()), RC_INVALID_INPUT);
  EXPECT_EQ(st[0], RC_INVALID_INPUT);
  EXPECT_EQ(st[1], RC_OK);
  expect_same(out[1], serial[3]);
  EXPECT_NE(c.error().find("state 0: rc_wheelset_state.y_m = nan"), std::string::npos) << c.error();
  std::vector<rc_wheelset_patch> one(2);
  EXPECT_EQ(rc_wheelset_batch_evaluate(c.h, 1, &states[0], 1, out.data(), 1, one.data(), st.data()),
            serial[0].patch_count[0] > 1 || serial[0].patch_count[1] > 1 ? RC_BUFFER_TOO_SMALL : RC_OK);
}

// Two handles on two threads at the same time give the numbers of the serial loop.
TEST(CApiWheelset, TwoHandlesOnTwoThreadsEqualSerial) {
  const std::vector<double> ys{-5e-3, 1e-3, 4e-3};
  std::vector<rc_wheelset_result> serial(2 * ys.size()), threaded(2 * ys.size());
  {
    CWheelset c(true, 1);
    for (std::size_t k = 0; k < ys.size(); ++k) {
      const rc_wheelset_state s = c_state(ys[k]);
      ASSERT_EQ(rc_wheelset_evaluate(c.h, &s, &serial[k]), RC_OK) << c.error();
    }
    CWheelset d(true, 1);
    for (std::size_t k = 0; k < ys.size(); ++k) {
      const rc_wheelset_state s = c_state(-ys[k], 1e-3);
      ASSERT_EQ(rc_wheelset_evaluate(d.h, &s, &serial[ys.size() + k]), RC_OK) << d.error();
    }
  }
  CWheelset a(true, 1), b(true, 1);
  std::vector<rc_status> status(2 * ys.size(), RC_INTERNAL);
  std::thread t1([&] {
    for (std::size_t k = 0; k < ys.size(); ++k) {
      const rc_wheelset_state s = c_state(ys[k]);
      status[k] = rc_wheelset_evaluate(a.h, &s, &threaded[k]);
    }
  });
  std::thread t2([&] {
    for (std::size_t k = 0; k < ys.size(); ++k) {
      const rc_wheelset_state s = c_state(-ys[k], 1e-3);
      status[ys.size() + k] = rc_wheelset_evaluate(b.h, &s, &threaded[ys.size() + k]);
    }
  });
  t1.join();
  t2.join();
  for (std::size_t k = 0; k < serial.size(); ++k) {
    EXPECT_EQ(status[k], RC_OK);
    expect_same(threaded[k], serial[k]);
  }
}

// rc_wheelset_options.slip_direction: elastic-slip by default (the C++ wheelset's), the others on
// request; each equals railcontact::Wheelset with that slip direction, and on the flange (y = -7 mm,
// deep slip with spin) they differ.
TEST(CApiWheelset, SlipDirectionEqualsTheCppWheelset) {
  rc_wheelset_options o;
  rc_wheelset_options_default(&o);
  EXPECT_EQ(o.slip_direction, RC_SLIP_ELASTIC);
  double right[4][3] = {};  // the right wheel's force (track axes), per slip direction
  for (const int direction : {RC_SLIP_RADIAL, RC_SLIP_FLEXIBILITY_WEIGHTED, RC_SLIP_RIGID, RC_SLIP_ELASTIC}) {
    CWheelset c(true, 0);
    ASSERT_EQ(rc_wheelset_get_options(c.h, &o), RC_OK);
    o.slip_direction = direction;
    ASSERT_EQ(rc_wheelset_set_options(c.h, &o), RC_OK) << c.error();
    WheelsetOptions options = coarse(true);
    options.nh_fastsim.bound.slip_direction = static_cast<SlipDirection>(direction);  // the same numbers
    Wheelset cpp(track(), options);
    const rc_wheelset_state s = c_state(-7e-3);
    rc_wheelset_result r;
    ASSERT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_OK) << c.error();
    const WheelsetResult e = cpp.evaluate(cpp_state(s));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(r.force_track_N[i], e.force_track_N[i]) << direction;
    for (int i = 0; i < 3; ++i) right[direction][i] = r.wheel_force_track_N[RC_WHEEL_RIGHT][i];
  }
  EXPECT_GT(std::hypot(right[1][0] - right[0][0], right[1][1] - right[0][1]), 100.0);  // N
  EXPECT_GT(std::hypot(right[2][0] - right[1][0], right[2][1] - right[1][1]), 100.0);  // N

  CWheelset c(true, 1);
  ASSERT_EQ(rc_wheelset_get_options(c.h, &o), RC_OK);
  o.slip_direction = -1;
  EXPECT_EQ(rc_wheelset_set_options(c.h, &o), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_options.slip_direction = -1 is not an rc_slip_direction"), std::string::npos)
      << c.error();
}

TEST(CApiWheelset, BadInputGivesStatusAndMessage) {
  CWheelset c(true, 1);
  rc_wheelset_state s = c_state(kNaN);
  rc_wheelset_result r;
  EXPECT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_state.y_m = nan m is not finite"), std::string::npos) << c.error();
  s = c_state(0.0);
  s.forward_speed_m_per_s = 0.0;
  EXPECT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_state.forward_speed_m_per_s = 0 m/s must lie in (0, 200] m/s"), std::string::npos) << c.error();
  s = c_state(0.0);
  s.rotation = 7;
  EXPECT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_state.rotation = 7"), std::string::npos) << c.error();
  s = c_state(0.2);  // off the track
  EXPECT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_EQ(rc_wheelset_evaluate(c.h, nullptr, &r), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_evaluate: state is null"), std::string::npos) << c.error();
  EXPECT_EQ(rc_wheelset_evaluate(nullptr, &s, &r), RC_INVALID_INPUT);
  // Nothing evaluated yet (the failures above leave no result).
  std::size_t count = 0;
  EXPECT_EQ(rc_wheelset_patch_count(c.h, RC_WHEEL_RIGHT, &count), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("no state has been evaluated"), std::string::npos) << c.error();

  // Files: an unknown file is RC_IO, naming it; the handle keeps its track.
  EXPECT_EQ(rc_wheelset_set_track(c.h, "/no/such/wheel.prw", default_rail_profile_path().string().c_str(), nullptr),
            RC_IO);
  EXPECT_NE(c.error().find("/no/such/wheel.prw"), std::string::npos) << c.error();
  EXPECT_EQ(rc_wheelset_set_track(c.h, nullptr, nullptr, nullptr), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("wheel_profile_path is null"), std::string::npos) << c.error();
  rc_track_parameters t;
  rc_track_parameters_default(&t);
  t.track_gauge_m = kNaN;
  EXPECT_EQ(rc_wheelset_set_track(c.h, "w", "r", &t), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_track_parameters.track_gauge_m = nan"), std::string::npos) << c.error();

  // Options: a refused set keeps the previous ones.
  rc_wheelset_options o, before;
  ASSERT_EQ(rc_wheelset_get_options(c.h, &before), RC_OK);
  o = before;
  o.friction_coefficient = kNaN;
  EXPECT_EQ(rc_wheelset_set_options(c.h, &o), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_options.friction_coefficient = nan"), std::string::npos) << c.error();
  o = before;
  o.solvers[0] = 9;
  EXPECT_EQ(rc_wheelset_set_options(c.h, &o), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("9 is not an rc_method"), std::string::npos) << c.error();
  o = before;
  o.solver_count = 2;
  o.solvers[1] = o.solvers[0];
  EXPECT_EQ(rc_wheelset_set_options(c.h, &o), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("given twice"), std::string::npos) << c.error();
  o = before;
  o.right_load_N = -1.0;
  EXPECT_EQ(rc_wheelset_set_options(c.h, &o), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("right wheel's vertical load"), std::string::npos) << c.error();
  rc_wheelset_options after;
  ASSERT_EQ(rc_wheelset_get_options(c.h, &after), RC_OK);
  EXPECT_EQ(after.friction_coefficient, before.friction_coefficient);
  EXPECT_EQ(after.solver_count, before.solver_count);

  // The patches' buffer and side.
  s = c_state(-7e-3);
  ASSERT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_OK) << c.error();
  ASSERT_EQ(rc_wheelset_patch_count(c.h, RC_WHEEL_RIGHT, &count), RC_OK);
  ASSERT_GE(count, 1u);
  std::vector<rc_wheelset_patch> p(count);
  EXPECT_EQ(rc_wheelset_patches(c.h, RC_WHEEL_RIGHT, count - 1, p.data()), RC_BUFFER_TOO_SMALL);
  EXPECT_EQ(rc_wheelset_patches(c.h, 2, count, p.data()), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("side = 2 is not an rc_wheel_side"), std::string::npos) << c.error();

  // No track yet.
  rc_wheelset* empty = nullptr;
  ASSERT_EQ(rc_wheelset_create(&empty), RC_OK);
  EXPECT_EQ(rc_wheelset_evaluate(empty, &s, &r), RC_INVALID_INPUT);
  rc_wheelset_destroy(empty);
}

// ---- The single patch with the approach given ---------------------------------------------------

std::string solver_error(const rc_solver* solver) {
  std::size_t length = 0;
  rc_solver_last_error(solver, nullptr, 0, &length);
  std::string message(length + 1, '\0');
  rc_solver_last_error(solver, message.data(), message.size(), nullptr);
  message.resize(length);
  return message;
}

// Hertz and an ellipse at an approach: the load whose Hertzian approach it is; a grid at an
// approach: the normal solver's position-driven solution, whose load given back gives the approach.
// The wheelset table through the C API: built, saved, loaded back and evaluated, it gives the C++
// table's lookup to the last digit; cancelling the build and bad use give statuses and messages.
TEST(CApiWheelsetTable, BuildSaveLoadEvaluateEqualsTheCppTable) {
  CWheelset w;
  const double y[] = {-0.5e-3, 0.0, 0.5e-3}, yaw[] = {0.0}, loads[] = {90e3, 110e3};
  rc_wheelset_state s;
  rc_wheelset_state_default(&s);
  s.y_m = 0.2e-3;
  s.yaw_rad = 1e-3;
  EXPECT_EQ(rc_wheelset_evaluate_table(w.h, &s, nullptr), RC_INVALID_INPUT);
  EXPECT_NE(w.error().find("the wheelset has no table"), std::string::npos) << w.error();
  ASSERT_EQ(rc_wheelset_table_build(w.h, y, 3, yaw, 1, loads, 2, nullptr, nullptr), RC_OK) << w.error();
  std::size_t ny = 0, nyaw = 0, nl = 0;
  ASSERT_EQ(rc_wheelset_table_size(w.h, &ny, &nyaw, &nl), RC_OK);
  EXPECT_EQ(ny * 100 + nyaw * 10 + nl, 312u);
  const std::string file = ::testing::TempDir() + "railcontact_c_api_wheelset_table.json";
  ASSERT_EQ(rc_wheelset_table_save(w.h, file.c_str()), RC_OK) << w.error();
  CWheelset back;
  ASSERT_EQ(rc_wheelset_table_load(back.h, file.c_str()), RC_OK) << back.error();
  rc_wheelset_options o;
  rc_wheelset_get_options(back.h, &o);
  o.right_load_N = 95e3;
  o.left_load_N = 105e3;
  ASSERT_EQ(rc_wheelset_set_options(back.h, &o), RC_OK);
  rc_wheelset_result r{};
  ASSERT_EQ(rc_wheelset_evaluate_table(back.h, &s, &r), RC_OK) << back.error();
  const WheelsetTable table = load_wheelset_table(file);
  WheelsetState state;
  state.position.lateral_displacement_m = 0.2e-3;
  state.position.yaw_rad = 1e-3;
  // The C API passes its tangential_in_balance (1 by default).
  const WheelsetResult expected = table.evaluate(state, WheelLoads{95e3, 105e3, false}, 0.3, true);
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 3; ++i) EXPECT_EQ(r.wheel_force_track_N[k][i], expected.wheels[k].force_track_N[i]);
  const std::vector<rc_wheelset_patch> right = back.patches(RC_WHEEL_RIGHT);
  ASSERT_EQ(right.size(), 1u);
  EXPECT_EQ(right[0].solver_count, 1);
  EXPECT_EQ(right[0].forces[0].F1_N, expected.wheels[0].patches[0].forces().F1_N);
  std::remove(file.c_str());

  s.y_m = 0.8e-3;  // outside the table
  EXPECT_EQ(rc_wheelset_evaluate_table(back.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(back.error().find("y = 0.8 mm lies outside the table's range [-0.5, 0.5] mm"), std::string::npos)
      << back.error();
  const auto cancel = [](size_t done, size_t, void*) { return done >= 2 ? 1 : 0; };
  EXPECT_EQ(rc_wheelset_table_build(w.h, y, 3, yaw, 1, loads, 2, cancel, nullptr), RC_CANCELLED);
  const double bad_yaw[] = {0.0, 0.5};
  EXPECT_EQ(rc_wheelset_table_build(w.h, y, 3, bad_yaw, 2, loads, 2, nullptr, nullptr), RC_INVALID_INPUT);
  EXPECT_NE(w.error().find("the yaw grid [0, 0.5] rad must lie in [-0.1, 0.1] rad"), std::string::npos) << w.error();
  EXPECT_EQ(rc_wheelset_table_load(w.h, "/nonexistent/t.json"), RC_IO);
}

// rc_wheelset_table_set_refinement: the next builds add y nodes where the contact jumps, as the
// C++ build with WheelsetTableRefinement does (the same grid to the last digit); the progress
// callback's total grows; a fraction outside [0, 1] is refused, naming it.
TEST(CApiWheelsetTable, TheRefinementAddsTheCppBuildsNodes) {
  CWheelset w;
  const double y[] = {-7.1e-3, -7.0e-3, -6.9e-3, -6.8e-3, -6.7e-3, -6.6e-3, -6.5e-3}, yaw[] = {0.0}, loads[] = {98.1e3};
  EXPECT_EQ(rc_wheelset_table_set_refinement(w.h, 1.5), RC_INVALID_INPUT);
  EXPECT_NE(w.error().find("lateral_force_fraction = 1.5 must lie in [0, 1]"), std::string::npos) << w.error();
  ASSERT_EQ(rc_wheelset_table_set_refinement(w.h, 0.01), RC_OK) << w.error();
  std::size_t last_total = 0;
  const auto progress = [](size_t, size_t total, void* user) {
    *static_cast<std::size_t*>(user) = total;
    return 0;
  };
  ASSERT_EQ(rc_wheelset_table_build(w.h, y, 7, yaw, 1, loads, 1, progress, &last_total), RC_OK) << w.error();
  std::size_t ny = 0, nyaw = 0, nl = 0;
  ASSERT_EQ(rc_wheelset_table_size(w.h, &ny, &nyaw, &nl), RC_OK);
  EXPECT_GT(ny, 7u);
  EXPECT_EQ(last_total, ny);
  WheelsetTableOptions o;
  o.refinement.lateral_force_fraction = 0.01;
  const WheelsetTable cpp = build_wheelset_table(default_wheelset_track(), {{y, y + 7}, {0.0}, {98.1e3}}, o);
  EXPECT_EQ(ny, cpp.grid().y_m.size());
}

// A table is used only with the track and options it was built for: rc_wheelset_table_load
// refuses one built for another element size, naming it; rc_wheelset_set_options keeps the table
// for a change of loads and mu and drops it for another material, and rc_wheelset_evaluate_table
// then names the call and the difference; so do the track calls for another track; a rolled
// state is refused.
TEST(CApiWheelsetTable, ATableIsUsedOnlyWithTheTrackAndOptionsItWasBuiltFor) {
  CWheelset w;
  const double y[] = {-0.5e-3, 0.5e-3}, yaw[] = {0.0}, loads[] = {90e3, 110e3};
  ASSERT_EQ(rc_wheelset_table_build(w.h, y, 2, yaw, 1, loads, 2, nullptr, nullptr), RC_OK) << w.error();
  const std::string file = ::testing::TempDir() + "railcontact_c_api_wheelset_table_settings.json";
  ASSERT_EQ(rc_wheelset_table_save(w.h, file.c_str()), RC_OK) << w.error();
  rc_wheelset_state s;
  rc_wheelset_state_default(&s);
  rc_wheelset_result r{};
  ASSERT_EQ(rc_wheelset_evaluate_table(w.h, &s, &r), RC_OK) << w.error();

  rc_wheelset_options o;
  rc_wheelset_get_options(w.h, &o);
  o.right_load_N = 95e3;
  o.friction_coefficient = 0.2;
  ASSERT_EQ(rc_wheelset_set_options(w.h, &o), RC_OK) << w.error();
  EXPECT_EQ(rc_wheelset_evaluate_table(w.h, &s, &r), RC_OK) << w.error();  // loads and mu are lookup inputs
  s.roll_rad = 1e-3;
  EXPECT_EQ(rc_wheelset_evaluate_table(w.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(w.error().find("rc_wheelset_state.roll_rad = 0.001 rad must be 0"), std::string::npos) << w.error();
  s.roll_rad = 0.0;

  o.youngs_modulus_Pa = 1e11;
  ASSERT_EQ(rc_wheelset_set_options(w.h, &o), RC_OK) << w.error();
  EXPECT_EQ(rc_wheelset_evaluate_table(w.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(w.error().find("the wheelset has no table: rc_wheelset_set_options dropped it: material E = 1e+11 Pa, "
                           "nu = 0.3 (rc_wheelset_options: youngs_modulus_Pa, poisson_ratio) differs from the "
                           "table's E = 2.1e+11 Pa, nu = 0.3"),
            std::string::npos)
      << w.error();

  CWheelset other;  // element size 0.5 mm
  rc_wheelset_get_options(other.h, &o);
  o.element_size_m = 0.2e-3;
  ASSERT_EQ(rc_wheelset_set_options(other.h, &o), RC_OK);
  EXPECT_EQ(rc_wheelset_table_load(other.h, file.c_str()), RC_INVALID_INPUT);
  EXPECT_NE(other.error().find("element-size 0.2 mm (rc_wheelset_options: element_size_m) differs from the table's 0.5 mm"),
            std::string::npos)
      << other.error();
  o.element_size_m = 0.5e-3;
  ASSERT_EQ(rc_wheelset_set_options(other.h, &o), RC_OK);
  ASSERT_EQ(rc_wheelset_table_load(other.h, file.c_str()), RC_OK) << other.error();
  ASSERT_EQ(rc_wheelset_set_default_track(other.h), RC_OK);  // the same track: the table stays
  EXPECT_EQ(rc_wheelset_evaluate_table(other.h, &s, &r), RC_OK) << other.error();
  rc_track_parameters wide;
  rc_track_parameters_default(&wide);
  wide.track_gauge_m = 1.445;
  const std::string profiles = std::string(RAILCONTACT_DATA_DIR) + "/profiles/";
  ASSERT_EQ(rc_wheelset_set_track(other.h, (profiles + "MBench_S1002_v3.prw").c_str(),
                                  (profiles + "MBench_UIC60_v3.prr").c_str(), &wide),
            RC_OK)
      << other.error();
  EXPECT_EQ(rc_wheelset_evaluate_table(other.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(other.error().find("the wheelset has no table: rc_wheelset_set_track dropped it: "), std::string::npos)
      << other.error();
  EXPECT_NE(other.error().find("was built for other track parameters"), std::string::npos) << other.error();
  std::remove(file.c_str());
}

TEST(CApiApproach, HertzEllipseAndGridAtAnApproach) {
  rc_solver* solver = nullptr;
  ASSERT_EQ(rc_solver_create(&solver), RC_OK);
  rc_settings settings;
  rc_settings_default(&settings);
  settings.mesh_value = 600;
  ASSERT_EQ(rc_solver_set_settings(solver, &settings), RC_OK);
  const Material steel{2.1e11, 0.3};
  const double A = 0.6, B = 1.4;
  const HertzContact reference = hertz_from_curvatures(A, B, 8e4, steel);
  rc_patch p{};
  p.kind = RC_GEOMETRY_HERTZ;
  p.A_per_m = A;
  p.B_per_m = B;
  p.normal_force_N = kNaN;  // ignored
  ASSERT_EQ(rc_solver_set_patch_at_approach(solver, &p, reference.approach_m), RC_OK) << solver_error(solver);
  rc_normal_result n;
  ASSERT_EQ(rc_solver_normal_result(solver, &n), RC_OK);
  EXPECT_NEAR(n.normal_force_N, 8e4, 8e4 * 1e-9);
  EXPECT_NEAR(n.approach_m, reference.approach_m, reference.approach_m * 1e-12);
  EXPECT_NEAR(n.a_m, reference.a_m, reference.a_m * 1e-9);

  p = rc_patch{};
  p.kind = RC_GEOMETRY_ELLIPSE;
  p.a_m = reference.a_m;
  p.b_m = reference.b_m;
  ASSERT_EQ(rc_solver_set_patch_at_approach(solver, &p, reference.approach_m), RC_OK) << solver_error(solver);
  ASSERT_EQ(rc_solver_normal_result(solver, &n), RC_OK);
  EXPECT_NEAR(n.normal_force_N, 8e4, 8e4 * 1e-6);
  EXPECT_EQ(rc_solver_set_patch_at_approach(solver, &p, -1e-6), RC_INVALID_INPUT);
  EXPECT_NE(solver_error(solver).find("must be positive"), std::string::npos) << solver_error(solver);
  EXPECT_EQ(rc_solver_set_patch_at_approach(solver, &p, kNaN), RC_INVALID_INPUT);
  EXPECT_NE(solver_error(solver).find("approach_m = nan m is not finite"), std::string::npos);

  // A grid of h = A x1² + B x2² − 40 µm (overlap at the position), approach 0.
  const int n1 = 40, n2 = 30;
  const double dx = 0.5e-3;
  std::vector<double> h(static_cast<std::size_t>(n1 * n2));
  for (int i2 = 0; i2 < n2; ++i2)
    for (int i1 = 0; i1 < n1; ++i1) {
      const double x1 = (i1 - 0.5 * (n1 - 1)) * dx, x2 = (i2 - 0.5 * (n2 - 1)) * dx;
      h[static_cast<std::size_t>(i2 * n1 + i1)] = A * x1 * x1 + B * x2 * x2 - 40e-6;
    }
  p = rc_patch{};
  p.kind = RC_GEOMETRY_GRID;
  p.grid_n1 = n1;
  p.grid_n2 = n2;
  p.grid_dx1_m = dx;
  p.grid_dx2_m = dx;
  p.grid_h_m = h.data();
  ASSERT_EQ(rc_solver_set_patch_at_approach(solver, &p, 0.0), RC_OK) << solver_error(solver);
  ASSERT_EQ(rc_solver_normal_result(solver, &n), RC_OK);
  Mesh mesh;
  mesh.n1 = n1;
  mesh.n2 = n2;
  mesh.dx1_m = mesh.dx2_m = dx;
  mesh.x1_first_m = -0.5 * (n1 - 1) * dx;
  mesh.x2_first_m = -0.5 * (n2 - 1) * dx;
  const NormalSolution cpp = solve_normal_contact_at_approach(mesh, h, 0.0, steel);
  // The patch's force: the sum over its elements (the C++ sum may add them in another order).
  EXPECT_NEAR(n.normal_force_N, cpp.normal_force_N, 1e-9 * cpp.normal_force_N);
  EXPECT_GT(n.normal_force_N, 1e3);
  rc_creepage c{1e-3, 0.0, 0.0};
  rc_forces f_approach, f_force;
  ASSERT_EQ(rc_solver_solve(solver, &c, &f_approach), RC_OK);
  // The load found, given back: the approach 0 again, and nearly the same forces.
  p.normal_force_N = n.normal_force_N;
  ASSERT_EQ(rc_solver_set_patch(solver, &p), RC_OK) << solver_error(solver);
  rc_normal_result m;
  ASSERT_EQ(rc_solver_normal_result(solver, &m), RC_OK);
  EXPECT_NEAR(m.approach_m, 0.0, 1e-9);
  ASSERT_EQ(rc_solver_solve(solver, &c, &f_force), RC_OK);
  EXPECT_NEAR(f_force.F1_N, f_approach.F1_N, 1e-6 * n.normal_force_N);
  // Separated everywhere at this approach: no contact.
  EXPECT_EQ(rc_solver_set_patch_at_approach(solver, &p, -1e-3), RC_NO_CONTACT);
  EXPECT_NE(solver_error(solver).find("no element comes into contact"), std::string::npos) << solver_error(solver);
  rc_solver_destroy(solver);
}

// Issue 28: the wheelset's rates, its track and its counts in their physical ranges, before any
// solve, naming the field.
TEST(CApiWheelsetRanges, RatesTrackAndCountsOutsideTheirRangesNameTheField) {
  CWheelset c;
  rc_wheelset_state s;
  rc_wheelset_state_default(&s);
  rc_wheelset_result r{};
  // A yaw rate of 1e6 rad/s gave xi = 37 522 and exit 0; 1e300 blamed the flexibilities.
  s.yaw_rate_rad_per_s = 1e6;
  EXPECT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_state.yaw_rate_rad_per_s = 1e+06 rad/s must lie in [-10, 10] rad/s"),
            std::string::npos)
      << c.error();
  rc_wheelset_state_default(&s);
  s.forward_speed_m_per_s = 1e6;
  EXPECT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_state.forward_speed_m_per_s = 1e+06 m/s must lie in (0, 200] m/s"),
            std::string::npos)
      << c.error();
  rc_wheelset_state_default(&s);
  s.rotation = RC_ROTATION_GIVEN;
  s.wheel_angular_velocity_rad_per_s = 1e5;
  EXPECT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_state.wheel_angular_velocity_rad_per_s = 100000 rad/s"), std::string::npos)
      << c.error();
  // Each rate in range, the wheels turning backwards: no rolling, naming the rotation, before the
  // tangential solve; turning forward too slowly: the kinematic creepage of a contact.
  s.wheel_angular_velocity_rad_per_s = -s.forward_speed_m_per_s / 0.46;
  EXPECT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("wheel_angular_velocity_rad_per_s = -43.4783 rad/s does not roll the wheels forward at the "
                           "forward speed V = 20 m/s"),
            std::string::npos)
      << c.error();
  s.wheel_angular_velocity_rad_per_s = 0.2 * s.forward_speed_m_per_s / 0.46;
  EXPECT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("wheel_angular_velocity_rad_per_s = 8.69565 rad/s at the forward speed V = 20 m/s gives "
                           "the right wheel's contact a longitudinal creepage xi = 1.3"),
            std::string::npos)
      << c.error();

  // The track: r0 = 1e-9 said "no contact"; 46 (a unit slip) ran a 46 m wheel.
  rc_track_parameters t;
  rc_track_parameters_default(&t);
  t.nominal_rolling_radius_m = 1e-9;
  EXPECT_EQ(rc_wheelset_set_track(c.h, "w", "r", &t), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_track_parameters.nominal_rolling_radius_m = 1e-09 m must lie in [0.04, 1.5] m"),
            std::string::npos)
      << c.error();
  t.nominal_rolling_radius_m = 46;
  EXPECT_EQ(rc_wheelset_set_track(c.h, "w", "r", &t), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("the value is in metres: 46 mm would be 0.046 m"), std::string::npos) << c.error();
  rc_track_parameters_default(&t);
  t.flange_back_distance_m = 1.43;
  EXPECT_EQ(rc_wheelset_set_track(c.h, "w", "r", &t), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("track_gauge_m - flange_back_distance_m = 1.435 - 1.43"), std::string::npos) << c.error();

  // Counts: (size_t)-1 states or patches per wheel, before anything is allocated.
  rc_wheelset_state_default(&s);
  EXPECT_EQ(rc_wheelset_batch_evaluate(c.h, SIZE_MAX, &s, 1, &r, 0, nullptr, nullptr), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_batch_evaluate: count = 18446744073709551615 states; at most "
                           "RC_MAX_WHEELSET_BATCH_STATES = 1000000"),
            std::string::npos)
      << c.error();
  rc_wheelset_patch patch{};
  EXPECT_EQ(rc_wheelset_batch_evaluate(c.h, 1, &s, 1, &r, SIZE_MAX, &patch, nullptr), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("patches_per_wheel = 18446744073709551615; at most RC_MAX_PATCHES_PER_WHEEL"),
            std::string::npos)
      << c.error();
}

// Free rolling through the C API: the C++ Wheelset's angular velocity and forces (the same code
// path: to rounding), each centred wheel's F1 below 0.1 % of mu Fz; pure rolling's angular velocity
// is V / r0; a rotation that is none of the three is refused.
TEST(CApiWheelset, FreeRollingIsTheCppWheelsets) {
  CWheelset c;
  rc_wheelset_state s;
  rc_wheelset_state_default(&s);
  rc_wheelset_result r;
  ASSERT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_OK) << c.error();
  double omega = 0.0;
  ASSERT_EQ(rc_wheelset_wheel_angular_velocity(c.h, &omega), RC_OK) << c.error();
  EXPECT_NEAR(omega, s.forward_speed_m_per_s / 0.46, 1e-12 * omega);
  s.rotation = RC_ROTATION_FREE;
  ASSERT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_OK) << c.error();
  ASSERT_EQ(rc_wheelset_wheel_angular_velocity(c.h, &omega), RC_OK) << c.error();
  WheelsetOptions options;
  options.element_size_m = 0.5e-3;
  WheelsetState state;
  state.velocity.free_rolling = true;
  const WheelsetResult cpp = Wheelset(default_wheelset_track(), options).evaluate(state);
  // The handle's warm start differs from the fresh Wheelset's: the normal solves agree to their
  // tolerance, the angular velocity to the free rolling's (1e-6 of mu Fz r0 in the moment: about
  // 1e-9 of Omega); 1e-6 of Omega lies well below its distance from V / r0 (8.6e-6 of it: checked
  // above 5e-6).
  EXPECT_NEAR(omega, cpp.state.velocity.wheel_angular_velocity_rad_per_s, 1e-6 * omega);
  EXPECT_GT(std::abs(omega - s.forward_speed_m_per_s / 0.46), 5e-6 * omega);
  for (int w = 0; w < 2; ++w) EXPECT_LT(std::abs(r.wheel_force_track_N[w][0]), 1e-3 * 0.3 * 98100.0);
  EXPECT_EQ(rc_wheelset_wheel_angular_velocity(c.h, nullptr), RC_INVALID_INPUT);
  s.rotation = 3;
  EXPECT_EQ(rc_wheelset_evaluate(c.h, &s, &r), RC_INVALID_INPUT);
  EXPECT_NE(c.error().find("rc_wheelset_state.rotation = 3 is not an rc_wheel_rotation (0 rolling, 1 given, 2 free)"),
            std::string::npos)
      << c.error();
}

// The options behind the CLI's --balance-solver and --reference-weighting and the set-up's
// track.nominal_radius_at, through the C API: the C++ Wheelset's numbers (the same code path: to
// 1e-12 relative), each with an effect (the balance solver moves the wheel heights, the depth
// weighting the contact angle of the two-lobe patch at y = −5.5 mm by several mrad, a taping line
// 1 mm from the profile origin moves ξ by about z_w(taping line) / r0), and out-of-range values
// named.
// rc_wheelset_options.contact_surface is the C++ wheelset's contact_surface: the conformal and the
// automatic surface give the C++ forces, each patch its spread, conformal weight and pressure
// resultant; a value outside rc_contact_surface is refused, naming it.
TEST(CApiWheelset, TheContactSurfaceIsTheCppWheelsets) {
  const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); };
  rc_wheelset_options o;
  rc_wheelset_options_default(&o);
  EXPECT_EQ(o.contact_surface, RC_SURFACE_PLANAR);
  const rc_wheelset_state flange = c_state(-6.5e-3);
  for (const int surface : {RC_SURFACE_CONFORMAL, RC_SURFACE_AUTO}) {
    CWheelset c(true, 0);
    ASSERT_EQ(rc_wheelset_get_options(c.h, &o), RC_OK);
    o.contact_surface = surface;
    ASSERT_EQ(rc_wheelset_set_options(c.h, &o), RC_OK) << c.error();
    rc_wheelset_result a;
    ASSERT_EQ(rc_wheelset_evaluate(c.h, &flange, &a), RC_OK) << c.error();
    WheelsetOptions options = coarse(true);
    options.contact_surface = surface == RC_SURFACE_AUTO ? ContactSurface::automatic : ContactSurface::conformal;
    Wheelset cpp(track(), options);
    const WheelsetResult e = cpp.evaluate(cpp_state(flange));
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(near(a.force_track_N[i], e.force_track_N[i])) << surface << " " << i;
    const std::vector<rc_wheelset_patch> patches = c.patches(RC_WHEEL_RIGHT);
    ASSERT_EQ(patches.size(), e.wheels[0].patches.size());
    const WheelsetPatch& q = e.wheels[0].patches[0];
    EXPECT_EQ(patches[0].conformal_weight, q.conformal_weight);
    EXPECT_EQ(patches[0].contact_angle_spread_rad, q.region.contact_angle_spread_rad);
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(near(patches[0].pressure_force_track_N[i], q.pressure_force_track_N[i]));
    EXPECT_GT(patches[0].contact_angle_spread_rad, 0.01);
    EXPECT_EQ(patches[0].conformal_weight, 1.0);  // the flange patch is conformal under auto as well
  }
  CWheelset bad(true, 0);
  ASSERT_EQ(rc_wheelset_get_options(bad.h, &o), RC_OK);
  o.contact_surface = 3;
  EXPECT_EQ(rc_wheelset_set_options(bad.h, &o), RC_INVALID_INPUT);
  EXPECT_NE(bad.error().find("rc_wheelset_options.contact_surface = 3 is not an rc_contact_surface"), std::string::npos)
      << bad.error();
}

TEST(CApiWheelset, BalanceSolverWeightingAndRadiusDatumAreTheCppWheelsets) {
  const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(1.0, std::abs(b)); };
  rc_wheelset_options o;
  rc_wheelset_options_default(&o);
  EXPECT_EQ(o.balance_solver, -1);
  EXPECT_EQ(o.reference_weighting, RC_WEIGHTING_SQUARED_GAP);

  // Balance by the exact solver's forces, nH-FastSim's the totals.
  const rc_wheelset_state flange = c_state(-6e-3);
  CWheelset first(true, 0, {RC_METHOD_NH_FASTSIM, RC_METHOD_EXACT}), by_exact(true, 0, {RC_METHOD_NH_FASTSIM, RC_METHOD_EXACT});
  ASSERT_EQ(rc_wheelset_get_options(by_exact.h, &o), RC_OK);
  o.balance_solver = RC_METHOD_EXACT;
  ASSERT_EQ(rc_wheelset_set_options(by_exact.h, &o), RC_OK) << by_exact.error();
  rc_wheelset_result a, b;
  ASSERT_EQ(rc_wheelset_evaluate(first.h, &flange, &a), RC_OK) << first.error();
  ASSERT_EQ(rc_wheelset_evaluate(by_exact.h, &flange, &b), RC_OK) << by_exact.error();
  WheelsetOptions options = coarse(true, {TangentialSolver::nh_fastsim, TangentialSolver::exact});
  options.balance_solver = TangentialSolver::exact;
  Wheelset cpp(track(), options);
  const WheelsetResult e = cpp.evaluate(cpp_state(flange));
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(near(b.force_track_N[i], e.force_track_N[i])) << i;
  EXPECT_GT(std::abs(b.wheel_vertical_displacement_m[RC_WHEEL_RIGHT] - a.wheel_vertical_displacement_m[RC_WHEEL_RIGHT]),
            1e-9);  // m
  o.balance_solver = RC_METHOD_FASTSIM;
  EXPECT_EQ(rc_wheelset_set_options(by_exact.h, &o), RC_INVALID_INPUT);
  EXPECT_NE(by_exact.error().find("rc_wheelset_options.balance_solver = 1 (fastsim) is not one of solvers"),
            std::string::npos)
      << by_exact.error();
  o.balance_solver = 7;
  EXPECT_EQ(rc_wheelset_set_options(by_exact.h, &o), RC_INVALID_INPUT);
  EXPECT_NE(by_exact.error().find("rc_wheelset_options.balance_solver = 7 is not an rc_method"), std::string::npos)
      << by_exact.error();

  // The depth weighting on the two-lobe patch.
  const rc_wheelset_state lobes = c_state(-5.5e-3);
  CWheelset squared(true, 0), depth(true, 0);
  ASSERT_EQ(rc_wheelset_get_options(depth.h, &o), RC_OK);
  o.reference_weighting = RC_WEIGHTING_DEPTH;
  ASSERT_EQ(rc_wheelset_set_options(depth.h, &o), RC_OK) << depth.error();
  ASSERT_EQ(rc_wheelset_evaluate(squared.h, &lobes, &a), RC_OK) << squared.error();
  ASSERT_EQ(rc_wheelset_evaluate(depth.h, &lobes, &b), RC_OK) << depth.error();
  WheelsetOptions depth_options = coarse(true);
  depth_options.search.weighting = ReferenceWeighting::depth;
  Wheelset cpp_depth(track(), depth_options);
  const WheelsetResult d = cpp_depth.evaluate(cpp_state(lobes));
  const std::vector<rc_wheelset_patch> ps = squared.patches(RC_WHEEL_RIGHT), pd = depth.patches(RC_WHEEL_RIGHT);
  ASSERT_EQ(pd.size(), d.wheels[0].patches.size());
  ASSERT_FALSE(ps.empty());
  EXPECT_TRUE(near(pd[0].contact_angle_rad, d.wheels[0].patches[0].region.contact_angle_rad));
  EXPECT_GT(std::abs(pd[0].contact_angle_rad - ps[0].contact_angle_rad), 3e-3);  // rad
  o.reference_weighting = 2;
  EXPECT_EQ(rc_wheelset_set_options(depth.h, &o), RC_INVALID_INPUT);
  EXPECT_NE(depth.error().find("rc_wheelset_options.reference_weighting = 2 is not an rc_reference_weighting"),
            std::string::npos)
      << depth.error();

  // r0 at a taping line 1 mm towards the field side of the profile origin.
  rc_track_parameters t;
  rc_track_parameters_default(&t);
  EXPECT_EQ(t.nominal_radius_at, RC_RADIUS_AT_PROFILE_ORIGIN);
  t.taping_line_from_flange_back_m = 0.071;
  const std::string wheel = default_wheel_profile_path().string(), rail = default_rail_profile_path().string();
  CWheelset origin(true, 0), taping(true, 0);
  ASSERT_EQ(rc_wheelset_set_track(origin.h, wheel.c_str(), rail.c_str(), &t), RC_OK) << origin.error();
  t.nominal_radius_at = RC_RADIUS_AT_TAPING_LINE;
  ASSERT_EQ(rc_wheelset_set_track(taping.h, wheel.c_str(), rail.c_str(), &t), RC_OK) << taping.error();
  rc_track_parameters back;
  ASSERT_EQ(rc_wheelset_get_track(taping.h, &back, nullptr), RC_OK);
  EXPECT_EQ(back.nominal_radius_at, RC_RADIUS_AT_TAPING_LINE);
  rc_wheelset_state centred;
  rc_wheelset_state_default(&centred);
  ASSERT_EQ(rc_wheelset_evaluate(origin.h, &centred, &a), RC_OK) << origin.error();
  ASSERT_EQ(rc_wheelset_evaluate(taping.h, &centred, &b), RC_OK) << taping.error();
  TrackWheelsetParameters parameters;
  parameters.taping_line_from_flange_back_m = 0.071;
  parameters.nominal_radius_at = NominalRadiusDatum::taping_line;
  Wheelset cpp_taping(WheelsetTrack(read_profile(wheel), read_profile(rail), parameters), coarse(true));
  const WheelsetResult tr = cpp_taping.evaluate(cpp_state(centred));
  const double z_taping_m = cpp_taping.track().pair(WheelSide::right).taping_line_z_m();
  const std::vector<rc_wheelset_patch> po = origin.patches(RC_WHEEL_RIGHT), pt = taping.patches(RC_WHEEL_RIGHT);
  ASSERT_FALSE(po.empty());
  ASSERT_FALSE(pt.empty());
  EXPECT_TRUE(near(pt[0].creepage.xi, tr.wheels[0].patches[0].creepage.xi));
  ASSERT_GT(std::abs(z_taping_m), 1e-5);  // m: the taping line is off the profile origin's height
  EXPECT_NEAR(std::abs(pt[0].creepage.xi - po[0].creepage.xi), std::abs(z_taping_m) / 0.46,
              0.05 * std::abs(z_taping_m) / 0.46);
  t.nominal_radius_at = 5;
  EXPECT_EQ(rc_wheelset_set_track(taping.h, wheel.c_str(), rail.c_str(), &t), RC_INVALID_INPUT);
  EXPECT_NE(taping.error().find("rc_track_parameters.nominal_radius_at = 5 is not an rc_nominal_radius_datum"),
            std::string::npos)
      << taping.error();
}

// rc_track_parameters.rail_cant_rad (default 0) cants the rail profile as the C++ track does: the
// upright UIC60 canted 1:40 through the C API gives the C++ Wheelset's forces (the same code path:
// within 1e-12 relative, the C API only copies), reads back, and a ratio given for the angle is
// refused naming the field, the value and the range.
TEST(CApiWheelset, RailCantIsTheCppWheelsets) {
  rc_track_parameters t;
  rc_track_parameters_default(&t);
  EXPECT_EQ(t.rail_cant_rad, 0.0);
  t.rail_cant_rad = std::atan(1.0 / 40.0);
  const std::string wheel = default_wheel_profile_path().string();
  const std::string rail = std::string(RAILCONTACT_SOURCE_DIR) + "/data/profiles/UIC60_upright.prr";
  CWheelset canted(true, 0);
  ASSERT_EQ(rc_wheelset_set_track(canted.h, wheel.c_str(), rail.c_str(), &t), RC_OK) << canted.error();
  rc_track_parameters back;
  ASSERT_EQ(rc_wheelset_get_track(canted.h, &back, nullptr), RC_OK);
  EXPECT_EQ(back.rail_cant_rad, std::atan(1.0 / 40.0));
  const rc_wheelset_state state = c_state(-2e-3);
  rc_wheelset_result r;
  ASSERT_EQ(rc_wheelset_evaluate(canted.h, &state, &r), RC_OK) << canted.error();
  TrackWheelsetParameters parameters;
  parameters.rail_cant_rad = std::atan(1.0 / 40.0);
  Wheelset cpp(WheelsetTrack(read_profile(wheel), read_profile(rail), parameters), coarse(true));
  const WheelsetResult expected = cpp.evaluate(cpp_state(state));
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(r.wheel_force_track_N[0][i], expected.wheels[0].force_track_N[i],
                1e-12 * std::abs(expected.wheels[0].force_track_N[2]));
  t.rail_cant_rad = 40.0;
  EXPECT_EQ(rc_wheelset_set_track(canted.h, wheel.c_str(), rail.c_str(), &t), RC_INVALID_INPUT);
  EXPECT_NE(canted.error().find("rc_track_parameters.rail_cant_rad = 40 rad must lie in [-0.1, 0.1] rad"),
            std::string::npos)
      << canted.error();
}

}  // namespace
}  // namespace railcontact
