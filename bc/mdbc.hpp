// Modified dynamic boundary conditions (mDBC; English et al. 2022, Comput. Part. Mech. 9:911-925)
// as a boundary module. Wall particles keep DBC's role in the pair loop (the fluid sees their
// pressure and velocity; they see fluid only), but their density no longer comes from the
// continuity equation: before every force evaluation each wall particle a takes it from its
// ghost node x_g = x_a + 2 n_a, its mirror image across the wall surface (n_a, the `normal`
// field, is the vector from the particle to the nearest surface point, geometry/wall_normals):
//   - at the ghost node, density and its gradient by the first-order consistent interpolation
//     of the fluid around it: the (D+1) x (D+1) system of Liu & Liu (2006)
//        sum_b V_b [ W_gb, (x_b - x_g)^T W_gb ; gradW_gb, gradW_gb (x_b - x_g)^T ] [rho; grad rho]
//          = sum_b m_b [ W_gb ; gradW_gb ],      V_b = m_b / rho_b, gradW at x_g;
//   - where that matrix is ill-conditioned (det < mdbc_det_min, the fluid covers too little of
//     the ghost's support, e.g. near the free surface) the Shepard average
//     sum m_b W / sum V_b W, without gradient;
//   - no fluid in the ghost's support: rho0;
//   - the wall particle's density (MdbcPressure), never below rho0 (as DBC's floor: a wall never
//     pulls fluid in):
//       linear (default): the extrapolation rho_g + (x_a - x_g) . grad rho_g (English et al.
//         2022; a Shepard ghost has no gradient: rho_g);
//       hydrostatic: the ghost's pressure carried to the wall by the momentum balance of fluid
//         at rest in the wall's frame, p_a = p(rho_g) + rho0 (g - a_a) . (x_a - x_g), then
//         rho_a = p^-1(p_a) by the Tait equation (the "pressure cloning" of English et al. 2025,
//         Comput. Fluids 303:106870, DualSPHysics 5.4's mDBC2; a_a the wall's acceleration, zero
//         on fixed bodies). It does not differentiate the SPH density field, whose gradient is
//         noise where the ghost's support is thin (a wedge of water on a beach, a film): there
//         the linear rule let water sink onto the wall and shot it off again (measured in
//         docs/method/boundaries.md#beaches-and-thin-water-pressure-hydrostatic).
// Wall velocity seen by the fluid (MdbcSlip): the body's (default, as DualSPHysics), no-slip
// 2 v_body - v_g, or free-slip (v_g with its normal component mirrored about the body's), v_g
// from the same interpolation. The body's velocity is restored after the force stage, so the
// state and checkpoints only hold the prescribed motion. Walls' continuity rates are set to zero
// after the forces: their density changes only through the ghost nodes.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cstddef>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/neighbours/gather.hpp"
#include "solver/physics/corrections.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"
#include "solver/time/step_hooks.hpp"

namespace swell {

// How a ghost node's value was obtained (the modes of the shared first-order system).
using GhostMode = CorrectionMode;

template <int D>
struct GhostValue {
  double rho = 0.0;
  Vec<D> grad = Vec<D>::Zero();  // density gradient (Corrected only; zero otherwise)
  Vec<D> vel = Vec<D>::Zero();   // interpolated fluid velocity (if asked for)
  double det = 0.0;              // determinant of the correction matrix
  GhostMode mode = GhostMode::Dry;
};

// Interpolates density (and velocity) of the fluid at point xg (inside the domain, grid sorted
// for the current positions) with the first-order system of solver/physics/corrections.hpp.
// Kernel: a kernel value type of solver/physics/kernels.hpp.
template <int D, class Kernel>
GhostValue<D> ghost_interpolate(const ParticleSet<D>& ps, const CellGrid<D>& grid,
                                const Kernel& kernel, const Vec<D>& xg, double det_min,
                                bool with_velocity) {
  FirstOrderSystem<D, D + 1> sys;  // column 0: density; 1..D: velocity
  const double s2 = kernel.support() * kernel.support();
  // The fluid near the support is collected in blocks by a SIMD test with a margin; each block
  // is then tested exactly (r^2 < s2 as one scalar pass would), its kernel values are taken in
  // SIMD lanes (sqrt, divisions, the kernel's branches; the Gaussian's exp stays scalar without
  // -ffast-math), and the sums run over it in the grid's
  // order with the same arithmetic as a plain scalar loop. The ghost values agree with that
  // loop's to the last bits (MdbcGhost.BlockedPassMatchesThePlainScalarPass; where the compiler
  // fuses multiply-adds differently they may differ in the last bit), and the runs' float state
  // was bit for bit that of the build before in every case of scripts/bitwise.
  constexpr int kChunk = 64, kBlock = 128;
  std::uint32_t idx[kBlock + kChunk + 8];
  Vec<D> rs[kBlock + kChunk];
  alignas(64) double r2s[kBlock + kChunk], ws[kBlock + kChunk], fs[kBlock + kChunk];
  int n = 0;
  const auto flush = [&] {
    int m = 0;
    for (int k = 0; k < n; ++k) {
      const std::uint32_t b = idx[k];
      const Vec<D> r = xg - ps.pos[b];  // x_g - x_b
      const double r2 = r.squaredNorm();
      if (!(r2 < s2)) continue;
      idx[m] = b;
      rs[m] = r;
      r2s[m++] = r2;
    }
#pragma omp simd
    for (int k = 0; k < m; ++k) {
      const double dist = std::sqrt(r2s[k]);
      ws[k] = kernel.w(dist);
      fs[k] = kernel.f(dist);
    }
    // The sums in a local copy the compiler can keep in registers.
    FirstOrderSystem<D, D + 1> acc = sys;
    for (int k = 0; k < m; ++k) {
      const std::uint32_t b = idx[k];
      const Vec<D>& r = rs[k];
      const double w = ws[k];
      const Vec<D> gw = r * fs[k];  // grad_g W(x_g - x_b)
      const double mb = ps.mass[b], V = mb / ps.rho[b];
      acc.add_moments(V, w, gw, r);
      // V_b rho_b = m_b: the density sums are taken with the mass itself.
      acc.B(0, 0) += mb * w;
      acc.B.template block<D, 1>(1, 0) += mb * gw;
      if (with_velocity) {
        const Vec<D> vb = widen<D>(ps.vel[b]);
        acc.B.template block<1, D>(0, 1) += (w * V) * vb.transpose();
        acc.B.template block<D, D>(1, 1) += V * gw * vb.transpose();
      }
    }
    sys = acc;
    n = 0;
  };
  if (grid.inside_domain(xg)) {
    static_assert(sizeof(Vec<D>) == D * sizeof(double), "positions must be D packed doubles");
    const double* P = ps.pos.data()->data();
    const double loose = s2 * (1.0 + 1e-9);  // the exact test is the flush's
    grid.for_each_neighbour_range(grid.cell_index(xg), [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t j = b; j < e; j += kChunk) {
        n = fluid_within<D>(P, ps.role.data(), xg.data(), loose, j, std::min(e, j + kChunk), idx,
                            n);
        if (n >= kBlock) flush();
      }
    });
  }
  flush();
  GhostValue<D> out;
  const auto s = sys.solve(det_min);
  out.det = s.det;
  out.mode = s.mode;
  if (s.mode == GhostMode::Dry) {
    out.det = 0.0;
    return out;
  }
  out.rho = s.X(0, 0);
  if (s.mode == GhostMode::Corrected) out.grad = s.X.template block<D, 1>(1, 0);
  if (with_velocity) out.vel = s.X.template block<1, D>(0, 1).transpose();
  return out;
}

template <int D>
class MdbcBoundary final : public BoundaryModel<D> {
 public:
  using Selection = WallsSeeFluid;
  // dbc_bodies[b] != 0: body b's walls are DBC walls (continuity, the rho0 floor, the body's
  // velocity), as in DbcBoundary; the others get their density from the ghost nodes.
  MdbcBoundary(MdbcSlip slip, double det_min, std::vector<std::uint8_t> dbc_bodies = {},
               MdbcPressure pressure = MdbcPressure::Linear)
      : slip_(slip), pressure_(pressure), det_min_(det_min), dbc_bodies_(std::move(dbc_bodies)) {
    // All zeros (a pure mDBC case, as the case setup passes it) is no DBC body at all: the
    // per-particle checks and the density-floor pass are then skipped.
    if (std::none_of(dbc_bodies_.begin(), dbc_bodies_.end(), [](std::uint8_t d) { return d; }))
      dbc_bodies_.clear();
  }
  std::string name() const override { return "mdbc"; }
  // Wall densities (and, without the default slip mode, velocities) from the ghost nodes.
  void before_forces(StepState<D>& s) override;
  // Sets the walls' density (images refreshed after it); nothing after the integration.
  bool reads_images_after_integration() const override { return false; }
  // The pair loop with DBC's selection (bc/mdbc.cpp).
  void forces(StepState<D>& s) override;
  // Walls' drho/dt = 0; wall velocities back to their body's.
  void after_forces(StepState<D>& s) override;
  // DBC bodies' walls: the density floor rho0 (as DbcBoundary).
  void finish_density(StepState<D>& s) override;

  // The checkpoint records that its walls were mDBC walls (a DBC checkpoint has no normals).
  void save(std::map<std::string, double>& out) const override {
    out["slip"] = static_cast<double>(slip_);
    out["pressure"] = static_cast<double>(pressure_);
    for (std::size_t b = 0; b < dbc_bodies_.size(); ++b)
      if (dbc_bodies_[b]) out["dbc_body." + std::to_string(b)] = 1.0;
  }
  void restore(const std::map<std::string, double>& in) override {
    if (in.find("slip") == in.end())
      throw std::invalid_argument(
          "checkpoint: written by a run with DBC walls, but the case asks for mDBC "
          "(physics.boundary); restart with the case the run was started with");
    // Checkpoints from before the option was there hold no entry: linear, the only rule then.
    const auto pr = in.find("pressure");
    const double rule = pr == in.end() ? static_cast<double>(MdbcPressure::Linear) : pr->second;
    if (rule != static_cast<double>(pressure_))
      throw std::invalid_argument(
          "checkpoint: written by a run whose mDBC walls took another pressure rule "
          "(physics.boundary.pressure); restart with the case the run was started with");
    // Every DBC body of the checkpoint must be one here, and the other way round.
    std::size_t saved = 0;
    for (auto it = in.lower_bound("dbc_body.");
         it != in.end() && it->first.starts_with("dbc_body."); ++it)
      ++saved;
    std::size_t here = 0;
    bool missing = false;
    for (std::size_t b = 0; b < dbc_bodies_.size(); ++b)
      if (dbc_bodies_[b])
        ++here, missing = missing || in.count("dbc_body." + std::to_string(b)) == 0;
    if (missing || saved != here)
      throw std::invalid_argument(
          "checkpoint: a body had another wall model (bodies[].boundary) in the run that wrote "
          "it; restart with the case the run was started with");
  }

  // Wall particles per mode in the last evaluation (for tests and the run summary).
  struct Counts {
    std::size_t corrected = 0, shepard = 0, dry = 0;
  };
  const Counts& counts() const { return counts_; }

 private:
  MdbcSlip slip_;
  MdbcPressure pressure_;
  double det_min_;
  std::vector<std::uint8_t> dbc_bodies_;
  bool dbc_wall(const ParticleSet<D>& ps, std::size_t i) const {
    return ps.body[i] < dbc_bodies_.size() && dbc_bodies_[ps.body[i]] != 0;
  }
  Counts counts_;
  std::vector<StateVec<D>> body_vel_;  // wall velocities while the forces see the slip velocity
};

template <int D>
std::unique_ptr<BoundaryModel<D>> make_mdbc(MdbcSlip slip, double det_min,
                                            std::vector<std::uint8_t> dbc_bodies = {},
                                            MdbcPressure pressure = MdbcPressure::Linear) {
  return std::make_unique<MdbcBoundary<D>>(slip, det_min, std::move(dbc_bodies), pressure);
}

extern template class MdbcBoundary<2>;
extern template class MdbcBoundary<3>;

}  // namespace swell
