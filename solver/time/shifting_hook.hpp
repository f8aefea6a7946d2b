// Particle shifting as a step hook: after each step's integration, every fluid particle is
// displaced by the Fickian shift of solver/physics/shifting.hpp, computed from the positions
// the step ended at and |v| dt of that step. Stateless (nothing in the checkpoint), so a
// restarted run continues bitwise.
#pragma once

#include <string>
#include <vector>

#include "solver/physics/kernels.hpp"
#include "solver/physics/shifting.hpp"
#include "solver/time/step_hooks.hpp"

namespace swell {

template <int D>
class ShiftingHook final : public StepHook<D> {
 public:
  explicit ShiftingHook(const ShiftingParams& p) : p_(p) {}
  std::string name() const override { return "shifting"; }
  bool changes_state_before_forces() const override { return false; }

  void after_integration(StepState<D>& s) override {
    ParticleSet<D>& ps = s.particles;
    stats_ = with_kernel<D>(s.params.kernel, s.params.h, [&](const auto& kernel) {
      if (s.exchange)  // several ranks: the halo's surface normals come from their owners
        return compute_shifting<D>(
            ps, s.grid, kernel, p_, s.params.dp, s.dt, work_,
            [&](std::vector<Vec<D>>& v, std::size_t gb) { s.exchange->refresh_vectors(v, gb); });
      return compute_shifting<D>(ps, s.grid, kernel, p_, s.params.dp, s.dt, work_);
    });
    const long n = static_cast<long>(ps.size());
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) ps.pos[i] += work_.shift[static_cast<std::size_t>(i)];
    if (p_.correct_density) {
      // Verlet's rho^(n-1) moves with the particle too (the symplectic scheme overwrites it).
      const bool prev = ps.rho_prev.size() >= ps.size();
#pragma omp parallel for schedule(static)
      for (long i = 0; i < n; ++i) {
        ps.rho[i] += work_.drho[static_cast<std::size_t>(i)];
        if (prev) ps.rho_prev[i] += work_.drho[static_cast<std::size_t>(i)];
      }
    }
  }

  const ShiftingStats& stats() const {
    return stats_;
  }

 private:
  ShiftingParams p_;
  ShiftingStats stats_;
  ShiftingWork<D> work_;
};

}  // namespace swell
