// The SPH course's corrections as solver options (off by default; solver/physics/corrections.hpp
// holds the operators):
//   - ShepardReinit: every N steps the fluid densities are re-initialised by the Shepard
//     (zeroth-order) interpolation rho_a = sum_b m_b W_ab / sum_b V_b W_ab over the fluid
//     particles around a (Colagrossi & Landrini 2003's filter), before that step's first force
//     evaluation. A Jacobi update (all from the old densities), so the result does not depend on
//     the order or thread count. The step counter is in the checkpoint: restart stays bitwise.
//   - KernelGradientCorrection: the momentum equation with the corrected kernel gradient
//     L_a gradW_ab (Bonet & Lok 1999). In the symmetric pressure + artificial-viscosity sum
//     every term of particle a carries gradW_ab, so L_a factors out of the sum:
//        dv_a/dt = L_a [ -sum_b m_b (P_a/rho_a^2 + P_b/rho_b^2 + Pi_ab) gradW_ab ] + g,
//     applied after the pair loop (the default loop is untouched). L_a from all neighbours the
//     fluid sees (fluid and walls), the identity where |det| of the moment matrix < det_min.
//     Linear momentum is no longer conserved exactly (L_a != L_b): `swell verify` measures by
//     how much. Not with laminar viscosity (its term is not along gradW_ab; refused by the case
//     reader).
#pragma once

#include <Eigen/Dense>
#include <map>
#include <string>
#include <vector>

#include "solver/physics/corrections.hpp"
#include "solver/physics/kernels.hpp"
#include "solver/time/step_hooks.hpp"

namespace swell {

template <int D>
class ShepardReinit final : public StepHook<D> {
 public:
  explicit ShepardReinit(int every) : every_(every) {}
  std::string name() const override { return "shepard"; }
  // Changes fluid densities before the forces; after the integration it only counts steps.
  bool reads_images_after_integration() const override { return false; }

  void before_forces(StepState<D>& s) override {
    if (!pending_) return;
    pending_ = false;
    ParticleSet<D>& ps = s.particles;
    const long n = static_cast<long>(ps.size());
    if (rho_.size() < ps.total()) rho_.resize(ps.total());  // once
    const CellGrid<D>& grid = s.grid;
    auto near = [&](const Vec<D>& x, auto&& fn) { grid.for_each_candidate_near(x, fn); };
    with_kernel<D>(s.params.kernel, s.params.h, [&](const auto& kernel) {
#pragma omp parallel for schedule(dynamic, 64)
      for (long i = 0; i < n; ++i) {
        if (!is_fluid(ps.role[i])) continue;
        // sum m W / sum V W = Shepard-normalised value of rho.
        rho_[i] =
            shepard_at<D>(ps, kernel, near, ps.pos[i], [&](std::uint32_t b) { return ps.rho[b]; });
      }
      return 0;
    });
    for (long i = 0; i < n; ++i)
      if (is_fluid(ps.role[i])) ps.rho[i] = rho_[i];
    ++count_;
  }
  void after_integration(StepState<D>&) override {
    if (++steps_ % every_ == 0) pending_ = true;
  }
  void save(std::map<std::string, double>& out) const override {
    out["steps"] = static_cast<double>(steps_);
    out["pending"] = pending_ ? 1.0 : 0.0;
  }
  void restore(const std::map<std::string, double>& in) override {
    if (auto it = in.find("steps"); it != in.end()) steps_ = static_cast<long>(it->second);
    if (auto it = in.find("pending"); it != in.end()) pending_ = it->second != 0.0;
  }
  long reinitialisations() const {
    return count_;
  }

 private:
  int every_;
  long steps_ = 0, count_ = 0;
  bool pending_ = false;
  std::vector<double> rho_;
};

template <int D>
class KernelGradientCorrection final : public StepHook<D> {
 public:
  explicit KernelGradientCorrection(double det_min) : det_min_(det_min) {}
  std::string name() const override { return "kgc"; }
  bool changes_state_before_forces() const override { return false; }
  bool reads_images_after_integration() const override { return false; }

  void after_forces(StepState<D>& s) override {
    ParticleSet<D>& ps = s.particles;
    const long n = static_cast<long>(ps.size());
    const Vec<D> g = s.params.gravity.template head<D>();
    const CellGrid<D>& grid = s.grid;
    auto near = [&](const Vec<D>& x, auto&& fn) { grid.for_each_candidate_near(x, fn); };
    auto all = [](std::uint32_t) { return true; };
    std::size_t corrected = 0;
    with_kernel<D>(s.params.kernel, s.params.h, [&](const auto& kernel) {
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : corrected)
      for (long i = 0; i < n; ++i) {
        if (!is_fluid(ps.role[i])) continue;
        double det = 0.0;
        const auto L =
            kgc_matrix<D>(ps, kernel, near, static_cast<std::uint32_t>(i), all, det_min_, &det);
        if (!(std::abs(det) >= det_min_)) continue;
        Vec<D>& a = s.forces.ace[i];
        a = L * (a - g) + g;
        ++corrected;
      }
      return 0;
    });
    corrected_ = corrected;
  }
  // Fluid particles corrected in the last evaluation (the rest had a singular moment matrix).
  std::size_t corrected() const {
    return corrected_;
  }

 private:
  double det_min_;
  std::size_t corrected_ = 0;
};

}  // namespace swell
