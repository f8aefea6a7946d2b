// The WCSPH pair evaluator: continuity with density diffusion and the symmetric momentum
// equation, built from the value types of this folder (kernel, viscosity, density diffusion;
// the EoS enters through the per-particle P/rho^2 and c buffers). Run by the pair driver
// (neighbours/pair_driver.hpp). No intrinsics here: the body is plain arithmetic the compiler
// vectorises (check -fopt-info-vec after a change; ARCHITECTURE.md).
//
// Equations (DESIGN.md, defaults as DualSPHysics):
//   drho_a/dt = sum_b m_b v_ab . gradW_ab + density diffusion (fluid-fluid pairs)
//   dv_a/dt   = -sum_b m_b (P_a/rho_a^2 + P_b/rho_b^2 + Pi_ab) gradW_ab + viscous + g
// A wall particle's results: drho/dt from its neighbours (per the selection policy) and, in
// `ace`, the force per unit mass the fluid exerts on it (for force gauges; never integrated).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

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
  struct Centre {
    double x0, x1, x2, v0, v1, v2;
    double rho, prs, cs, dd_weight;
    bool fluid;
  };

  // prs: P/rho^2 and cs: c of every active particle; drho, ace: the outputs.
  WcsphEvaluator(const ParticleSet<D>& ps, const SolverParams& prm, const Kernel& kernel,
                 const double* prs, const double* cs, double* drho, Vec<D>* ace)
      : kernel_(kernel),
        av_{prm.alpha, prm.h},
        lam_{4.0 * prm.nu},
        dd_{prm.diffusion != DiffusionModel::None ? prm.delta * prm.h * prm.c0 : 0.0,
            prm.diffusion == DiffusionModel::Fourtakas ? prm.rho0 / (prm.c0 * prm.c0) : 0.0},
        eta2_(prm.eta2()),
        c0_(prm.c0),
        inv_rho0_(1.0 / prm.rho0),
        g_(prm.gravity.template head<D>()),
        P_(ps.pos.data()->data()),
        U_(ps.vel.data()->data()),
        rho_(ps.rho.data()),
        mass_(ps.mass.data()),
        m0_(ps.mass.empty() ? 0.0 : ps.mass.front()),
        prs_(prs),
        cs_(cs),
        drho_(drho),
        ace_(ace) {}

  Centre centre(std::uint32_t a, bool fluid_a) const {
    Centre c{};
    c.x0 = P_[a * D];
    c.x1 = P_[a * D + 1];
    c.x2 = D == 3 ? P_[a * D + D - 1] : 0.0;
    c.v0 = U_[a * D];
    c.v1 = U_[a * D + 1];
    c.v2 = D == 3 ? U_[a * D + D - 1] : 0.0;
    c.rho = rho_[a];
    c.prs = prs_[a];
    if constexpr (VM != ViscosityModel::Artificial) {
      c.cs = 0.0;  // not used (and the buffer is not filled)
    } else if constexpr (kTait7) {
      const double ra = c.rho * inv_rho0_;
      c.cs = c0_ * ra * ra * ra;
    } else {
      c.cs = cs_[a];
    }
    c.dd_weight = dd_.weight(fluid_a || Select::kWallsDiffuse);
    c.fluid = fluid_a;
    return c;
  }

  // s0: drho/dt, s1..s3: acceleration, mx: viscous time-step signal. In 2D the third axis is
  // not used and compiles away. Real pairs have r2 > 1e-18 (gather); a padding entry
  // (r_ab = v_ab = 0) gets a finite kernel factor, so every term is exactly zero for it.
  void pair(const Centre& a, std::uint32_t e, double& drho, double& ac0, double& ac1, double& ac2,
            double& vdt) const {
    const std::uint32_t b = e & ~kWallBit;
    const double fluid_b = (e & kWallBit) ? 0.0 : 1.0;
    const double r0 = a.x0 - P_[b * D], r1 = a.x1 - P_[b * D + 1];
    const double r2c = D == 3 ? a.x2 - P_[b * D + D - 1] : 0.0;
    const double w0 = a.v0 - U_[b * D], w1 = a.v1 - U_[b * D + 1];
    const double w2 = D == 3 ? a.v2 - U_[b * D + D - 1] : 0.0;
    const double r2 = r0 * r0 + r1 * r1 + r2c * r2c;
    const double vr = w0 * r0 + w1 * r1 + w2 * r2c;                                 // v_ab . r_ab
    const double grx = g_[0] * r0 + g_[1] * r1 + (D == 3 ? g_[D - 1] * r2c : 0.0);  // g . r_ab
    // gradW_ab = r_ab fr
    const double fr = kernel_.fs(std::sqrt(std::max(r2, 1e-18)));
    const double m_b = kOneMass ? m0_ : mass_[b], rho_b = rho_[b];
    const double inv_r2e = 1.0 / (r2 + eta2_);
    const double r_dot_gradw = r2 * fr;
    drho += m_b * fr * vr;  // m_b v_ab . gradW_ab
    // Approaching pairs: the viscous time-step signal and Monaghan's Pi_ab.
    const double mu = av_.mu(vr, inv_r2e);
    vdt = vdt > -mu ? vdt : -mu;
    double pterm = a.prs + prs_[b];
    if constexpr (VM == ViscosityModel::Artificial) {
      double cs_b;
      if constexpr (kTait7) {
        const double rb = rho_b * inv_rho0_;
        cs_b = c0_ * rb * rb * rb;
      } else {
        cs_b = cs_[b];
      }
      pterm += av_.pi(mu, a.cs, cs_b, a.rho, rho_b);
    }
    const double fp = -m_b * pterm * fr;
    const double fv =
        VM == ViscosityModel::Laminar ? lam_.factor(m_b, r_dot_gradw, a.rho, rho_b, inv_r2e) : 0.0;
    ac0 += fp * r0 + fv * w0;
    ac1 += fp * r1 + fv * w1;
    ac2 += fp * r2c + fv * w2;
    drho += dd_.term(fluid_b, a.dd_weight, dd_.drho(a.rho, rho_b, grx), r_dot_gradw, inv_r2e,
                     m_b / rho_b);
  }

  double finish(std::uint32_t a, const Centre& c, double drho, double ac0, double ac1, double ac2,
                double vdt) {
    const double acc[3] = {ac0, ac1, ac2};
    drho_[a] = drho;
    // A wall particle's `ace` is the force per unit mass the fluid exerts on it (no g).
    for (int d = 0; d < D; ++d) ace_[a][d] = acc[d] + (c.fluid ? g_[d] : 0.0);
    return c.fluid ? vdt : 0.0;
  }

  void idle(std::uint32_t a) {
    drho_[a] = 0.0;
    ace_[a] = Vec<D>::Zero();
  }

 private:
  Kernel kernel_;
  ArtificialViscosity av_;
  LaminarViscosity lam_;
  DensityDiffusion dd_;
  double eta2_, c0_, inv_rho0_;
  Vec<D> g_;
  const double* P_;
  const StateReal *U_, *rho_;  // widened to double where read
  const double* mass_;
  double m0_;
  const double *prs_, *cs_;
  double* drho_;
  Vec<D>* ace_;
};

}  // namespace swell
