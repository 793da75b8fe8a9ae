// The cases and the record of the reproducibility test across the kernels' instruction-set
// versions (tests/test_kernel_versions.cpp): the same text from every version, byte for byte.
// Built into the test suite (the kernels the build's dispatch picks for this CPU) and into
// kernels_portable and kernels_avx2 (the same sources without the versions above them).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "base/params.hpp"
#include "base/result.hpp"
#include "run/run.hpp"

namespace mpmstab::kernel_versions {

// Every basis, transfer and update order, a failing run, a free surface with a small-mass
// treatment, a block crossing cells, the neo-Hookean law and the B-splines' walls: each path of
// the kernels that has a vector version.
inline std::vector<RunParams> cases() {
  std::vector<RunParams> out;
  auto base = [] {
    RunParams p;
    p.E = 100;
    p.A = 0.02;
    p.T = 0.2;
    p.cells = 40;
    p.dt = 1e-3;
    p.observe.final_state = true;
    p.observe.energy = true;
    return p;
  };
  for (Method m : {Method::mpm, Method::gimp, Method::cpgimp, Method::bspline2, Method::bspline3,
                   Method::cpdi}) {
    RunParams p = base();
    p.method = m;
    out.push_back(p);
  }
  for (Transfer t :
       {Transfer::pic, Transfer::blend, Transfer::apic, Transfer::xpic, Transfer::fmpm}) {
    RunParams p = base();
    p.method = Method::gimp;
    p.transfer = t;
    out.push_back(p);
  }
  for (UpdateOrder u : {UpdateOrder::usf, UpdateOrder::musl}) {
    RunParams p = base();
    p.update = u;
    out.push_back(p);
  }
  RunParams failing = base();  // fails with a large step
  failing.method = Method::mpm;
  failing.dt = 8e-3;
  failing.T = 1;
  out.push_back(failing);
  RunParams impulsive = base();
  impulsive.scene = SceneKind::impulsive;
  impulsive.method = Method::mpm;
  impulsive.small_mass = SmallMass::momentum;
  impulsive.observe.energy = false;
  out.push_back(impulsive);
  RunParams block = base();
  block.scene = SceneKind::block;
  block.bc = Boundary::periodic;
  block.A = 0.1;
  out.push_back(block);
  // A material law other than the linear one (the stress update's own pass), 3 and 4 nodes.
  for (Method m : {Method::gimp, Method::cpgimp}) {
    RunParams steffen = base();
    steffen.scene = SceneKind::steffen;
    steffen.method = m;
    out.push_back(steffen);
  }
  // The B-splines' other walls: none (periodic) and the boundary-modified splines.
  RunParams mode = base();
  mode.scene = SceneKind::mode;
  mode.bc = Boundary::periodic;
  mode.method = Method::bspline3;
  out.push_back(mode);
  for (Method m : {Method::bspline2, Method::bspline3}) {
    RunParams modified = base();
    modified.method = m;
    modified.walls = Walls::modified;
    out.push_back(modified);
  }
  return out;
}

// A value as exact text (hexadecimal floating point: every bit).
inline std::string bits(double v) {
  char s[40];
  std::snprintf(s, sizeof s, "%a", v);
  return s;
}
inline std::string bits(const std::optional<double>& v) {
  return v ? bits(*v) : "none";
}

// What a run computed, every bit of it: the verdict, the step count, the errors, eq. (108), the
// energies and every particle's final state.
inline std::string record(const RunResult& r) {
  std::string s = std::to_string(r.steps) + " " + (r.failure ? "failed" : "survived") + " " +
                  bits(r.max_error) + " " + bits(r.max_error_over_time) + " " +
                  bits(r.dt_stable_min) + " " + bits(r.energy_error_max) + "\n";
  if (r.final_state) {
    const FinalState& f = *r.final_state;
    for (const Eigen::ArrayXd* a : {&f.x, &f.v, &f.F, &f.sigma}) {
      for (const double v : *a)
        s += bits(v) + " ";
      s += "\n";
    }
  }
  return s;
}

inline std::string all_records() {
  std::string s;
  for (const RunParams& p : cases())
    s += record(run(p));
  return s;
}

}  // namespace mpmstab::kernel_versions
