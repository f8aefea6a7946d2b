// The WCSPH pair evaluator: continuity with density diffusion and the symmetric momentum
// equation, built from the value types of this folder (kernel, viscosity, density diffusion;
// the EoS enters through the per-particle P/rho^2 and c buffers). Run by the pair driver
// (neighbours/pair_driver.hpp). No intrinsics here: the body is plain arithmetic the compiler
// vectorises (check -fopt-info-vec after a change; ARCHITECTURE.md). Its arithmetic is
// PairReal (types.hpp: float unless the double-state build), with r_ab taken from the double
// positions; the rates are stored in double.
//
// Equations (docs/method/equations.md; defaults as DualSPHysics):
//   drho_a/dt = sum_b m_b v_ab . gradW_ab + density diffusion (fluid-fluid pairs)
//   dv_a/dt   = -sum_b m_b (P_a/rho_a^2 + P_b/rho_b^2 + Pi_ab) gradW_ab + viscous + g
// A wall particle's results: drho/dt from its neighbours (per the selection policy) and, in
// `ace`, the force per unit mass the fluid exerts on it (for force gauges; never integrated).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "solver/neighbours/gather.hpp"
#include "solver/physics/density_diffusion.hpp"
#include "solver/physics/viscosity.hpp"
#include "solver/solver_params.hpp"
#include "solver/state/particle_set.hpp"

namespace swell {

// kTait7 (artificial viscosity only): the signal speed c_b of the default Tait gamma = 7 is
// computed in the loop as c0 (rho_b/rho0)^3, three multiplications instead of one more gather
// per pair (gathers are the loop's most expensive instructions; this keeps B3D's speed). Any
// other equation of state reads c from the buffer filled by compute_pressure.
// kOneMass: every particle (images included) has the same mass, read once instead of gathered
// per pair (the same value, so the same results; a lattice fill makes every mass rho0 dp^D).
template <int D, class Kernel, ViscosityModel VM, class Select, bool kTait7 = false,
          bool kOneMass = false>
class WcsphEvaluator {
 public:
  using Real = PairReal;  // the pair terms' arithmetic and the sums' type (types.hpp)
  struct Centre {
    double x0, x1, x2;  // positions stay double: r_ab is taken in double
    Real v0, v1, v2;
    Real rho, prs, cs, dd_weight;
    bool fluid;
  };

  // prs: P/rho^2 and cs: c of every active particle; drho, ace: the outputs; rows: kStaged's
  // rows (ForceBuffers::rows).
  WcsphEvaluator(const ParticleSet<D>& ps, const SolverParams& prm, const Kernel& kernel,
                 const double* prs, const double* cs, double* drho, Vec<D>* ace,
                 const float* rows = nullptr)
      : kernel_(kernel),
        av_{static_cast<Real>(prm.alpha), static_cast<Real>(prm.h)},
        lam_{static_cast<Real>(4.0 * prm.nu)},
        dd_{static_cast<Real>(prm.diffusion != DiffusionModel::None ? prm.delta * prm.h * prm.c0
                                                                    : 0.0),
            static_cast<Real>(
                prm.diffusion == DiffusionModel::Fourtakas ? prm.rho0 / (prm.c0 * prm.c0) : 0.0)},
        support2_(static_cast<Real>(kernel.support() * kernel.support())),
        eta2_(static_cast<Real>(prm.eta2())),
        c0_(static_cast<Real>(prm.c0)),
        inv_rho0_(static_cast<Real>(1.0 / prm.rho0)),
        g_{static_cast<Real>(prm.gravity[0]), static_cast<Real>(prm.gravity[1]),
           static_cast<Real>(prm.gravity[2])},
        gd_(prm.gravity.template head<D>()),
        P_(ps.pos.data()->data()),
        U_(ps.vel.data()->data()),
        rho_(ps.rho.data()),
        mass_(ps.mass.data()),
        m0_(ps.mass.empty() ? Real(0) : static_cast<Real>(ps.mass.front())),
        prs_(prs),
        cs_(cs),
        drho_(drho),
        ace_(ace),
        rows_(rows) {}

  Centre centre(std::uint32_t a, bool fluid_a) const {
    Centre c{};
    c.x0 = P_[a * D];
    c.x1 = P_[a * D + 1];
    c.x2 = D == 3 ? P_[a * D + D - 1] : 0.0;
    c.v0 = static_cast<Real>(U_[a * D]);
    c.v1 = static_cast<Real>(U_[a * D + 1]);
    c.v2 = D == 3 ? static_cast<Real>(U_[a * D + D - 1]) : Real(0);
    c.rho = static_cast<Real>(rho_[a]);
    c.prs = static_cast<Real>(prs_[a]);
    if constexpr (VM != ViscosityModel::Artificial) {
      c.cs = 0;  // not used (and the buffer is not filled)
    } else if constexpr (kTait7) {
      const Real ra = c.rho * inv_rho0_;
      c.cs = c0_ * ra * ra * ra;
    } else {
      c.cs = static_cast<Real>(cs_[a]);
    }
    c.dd_weight = dd_.weight(fluid_a || Select::kWallsDiffuse);
    c.fluid = fluid_a;
    return c;
  }

  // Staging (float pair terms): the driver copies each block of 16 neighbours' values
  // into lanes (gather.hpp: one 16-byte row load a neighbour and a transpose, instead of six
  // scalar loads and inserts; gathers are slower still on this CPU) and runs pair_lane() on
  // them. The rows (v_x, v_y, rho, P/rho^2 rounded to float) are ForceBuffers::rows, filled
  // by compute_pressure; the values are those pair() reads, so the results are the same bits.
  // In 3D the positions and velocities are staged from the state itself and rho, P/rho^2 by
  // plain loads (no rows: 16 B more per particle would pass the memory target).
  static constexpr bool kStaged = std::is_same_v<Real, float>;
  struct Lanes {
    alignas(64) double x0[16];
    alignas(64) double x1[16];
    alignas(64) double x2[16];
    alignas(64) float v0[16];
    alignas(64) float v1[16];
    alignas(64) float v2[16];
    alignas(64) float rho[16];
    alignas(64) float prs[16];
  };
  void stage(const std::uint32_t* e, Lanes& l) const {
    if constexpr (D == 2)
      stage_rows_2d(P_, rows_, e, l.x0, l.x1, l.v0, l.v1, l.rho, l.prs);
    else
      stage_rows_3d(P_, U_, rho_, prs_, e, l.x0, l.x1, l.x2, l.v0, l.v1, l.v2, l.rho, l.prs);
  }

  // s0: drho/dt, s1..s3: acceleration, mx: viscous time-step signal. In 2D the third axis is
  // not used and compiles away. Real pairs have r2 > 1e-18 (gather); a padding entry
  // (r_ab = v_ab = 0) gets a finite kernel factor, so every term is exactly zero for it.
  void pair(const Centre& a, std::uint32_t e, Real& drho, Real& ac0, Real& ac1, Real& ac2,
            Real& vdt) const {
    const std::uint32_t b = e & ~kWallBit;
    terms(a, e, P_[b * D], P_[b * D + 1], D == 3 ? P_[b * D + D - 1] : 0.0,
          static_cast<Real>(U_[b * D]), static_cast<Real>(U_[b * D + 1]),
          D == 3 ? static_cast<Real>(U_[b * D + D - 1]) : Real(0), static_cast<Real>(rho_[b]),
          static_cast<Real>(prs_[b]), drho, ac0, ac1, ac2, vdt);
  }
  // The same pair from staged lanes (lane l holds entry e's values).
  void pair_lane(const Centre& a, std::uint32_t e, const Lanes& s, std::uint32_t l, Real& drho,
                 Real& ac0, Real& ac1, Real& ac2, Real& vdt) const {
    terms(a, e, s.x0[l], s.x1[l], D == 3 ? s.x2[l] : 0.0, s.v0[l], s.v1[l],
          D == 3 ? s.v2[l] : Real(0), s.rho[l], s.prs[l], drho, ac0, ac1, ac2, vdt);
  }

 private:
  // One pair's terms from b's values (xb: position; vb: velocity; rho_b; prs_b: P_b/rho_b^2).
  void terms(const Centre& a, std::uint32_t e, double xb0, double xb1, double xb2, Real vb0,
             Real vb1, Real vb2, Real rho_b, Real prs_b, Real& drho, Real& ac0, Real& ac1,
             Real& ac2, Real& vdt) const {
    const std::uint32_t b = e & ~kWallBit;
    const Real fluid_b = (e & kWallBit) ? Real(0) : Real(1);
    // r_ab in double, then rounded: its relative error is Real's, whatever the coordinates.
    const Real r0 = static_cast<Real>(a.x0 - xb0);
    const Real r1 = static_cast<Real>(a.x1 - xb1);
    const Real r2c = D == 3 ? static_cast<Real>(a.x2 - xb2) : Real(0);
    const Real w0 = a.v0 - vb0;
    const Real w1 = a.v1 - vb1;
    const Real w2 = D == 3 ? a.v2 - vb2 : Real(0);
    const Real r2 = r0 * r0 + r1 * r1 + r2c * r2c;
    const Real vr = w0 * r0 + w1 * r1 + w2 * r2c;                                     // v_ab . r_ab
    const Real grx = g_[0] * r0 + g_[1] * r1 + (D == 3 ? g_[D - 1] * r2c : Real(0));  // g . r_ab
    // gradW_ab = r_ab fr
    // The float gather admits a few pairs just beyond the support (its margin): this test on
    // r_ab from the double positions decides, the same for (a, b) and (b, a). (A product, not
    // a branch: the kernel's division must stay unconditional for the loop to vectorise.)
    const Real inside = std::is_same_v<Real, float> ? static_cast<Real>(r2 < support2_) : Real(1);
    const Real fr = kernel_.fs(std::sqrt(std::max(r2, Real(1e-18)))) * inside;
    const Real m_b = kOneMass ? m0_ : static_cast<Real>(mass_[b]);
    const Real inv_r2e = Real(1) / (r2 + eta2_);
    const Real r_dot_gradw = r2 * fr;
    drho += m_b * fr * vr;  // m_b v_ab . gradW_ab
    // Approaching pairs: the viscous time-step signal and Monaghan's Pi_ab.
    const Real mu = av_.mu(vr, inv_r2e) * inside;  // the time-step signal too (1 in double)
    vdt = vdt > -mu ? vdt : -mu;
    Real pterm = a.prs + prs_b;
    if constexpr (VM == ViscosityModel::Artificial) {
      Real cs_b;
      if constexpr (kTait7) {
        const Real rb = rho_b * inv_rho0_;
        cs_b = c0_ * rb * rb * rb;
      } else {
        cs_b = static_cast<Real>(cs_[b]);
      }
      pterm += av_.pi(mu, a.cs, cs_b, a.rho, rho_b);
    }
    const Real fp = -m_b * pterm * fr;
    const Real fv = VM == ViscosityModel::Laminar
                        ? lam_.factor(m_b, r_dot_gradw, a.rho, rho_b, inv_r2e)
                        : Real(0);
    ac0 += fp * r0 + fv * w0;
    ac1 += fp * r1 + fv * w1;
    ac2 += fp * r2c + fv * w2;
    drho += dd_.term(fluid_b, a.dd_weight, dd_.drho(a.rho, rho_b, grx), r_dot_gradw, inv_r2e,
                     m_b / rho_b);
  }

 public:
  double finish(std::uint32_t a, const Centre& c, Real drho, Real ac0, Real ac1, Real ac2,
                Real vdt) {
    const double acc[3] = {ac0, ac1, ac2};
    drho_[a] = drho;
    // A wall particle's `ace` is the force per unit mass the fluid exerts on it (no g).
    for (int d = 0; d < D; ++d) ace_[a][d] = acc[d] + (c.fluid ? gd_[d] : 0.0);
    return c.fluid ? vdt : 0.0;
  }

  void idle(std::uint32_t a) {
    drho_[a] = 0.0;
    ace_[a] = Vec<D>::Zero();
  }

 private:
  Kernel kernel_;
  ArtificialViscosity<Real> av_;
  LaminarViscosity<Real> lam_;
  DensityDiffusion<Real> dd_;
  Real support2_, eta2_, c0_, inv_rho0_;
  Real g_[3];
  Vec<D> gd_;  // g in double, added to the fluid's sums
  const double* P_;
  const StateReal *U_, *rho_;
  const double* mass_;
  Real m0_;
  const double *prs_, *cs_;
  double* drho_;
  Vec<D>* ace_;
  const float* rows_;  // kStaged: (v_x, v_y, rho, P/rho^2) per particle
};

}  // namespace swell
