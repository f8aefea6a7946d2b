// Particle state as a structure of arrays.
//
// Active particles occupy [0, size()); excluded particles are moved past the end by
// CellGrid::sort and stay there (counted, never simulated again). Every array listed in
// for_each_array() is permuted together when particles are reordered by cell; scratch
// buffers are kept so reordering never allocates once capacity is reached.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/types.hpp"

namespace swell {

template <int D>
struct ParticleSet {
  using V = Vec<D>;

  // Evolved state.
  std::vector<V> pos, vel;
  std::vector<double> rho;
  // Integrator memory: x^n, v^n, rho^n (symplectic) or v^{n-1}, rho^{n-1} (Verlet).
  std::vector<V> pos0, vel0;
  std::vector<double> rho0;
  // Constant per particle.
  std::vector<double> mass;
  std::vector<Kind> kind;
  std::vector<std::uint16_t> body;
  std::vector<std::uint32_t> id;

  std::size_t n_active = 0;

  std::size_t size() const { return n_active; }
  std::size_t total() const { return pos.size(); }

  void reserve(std::size_t n) {
    for_each_array([n](auto& a) { a.reserve(n); });
  }

  void add(const V& x, const V& v, double density, double m, Kind k, std::uint16_t body_id) {
    const auto next_id = static_cast<std::uint32_t>(pos.size());
    pos.push_back(x);
    vel.push_back(v);
    rho.push_back(density);
    pos0.push_back(x);
    vel0.push_back(v);
    rho0.push_back(density);
    mass.push_back(m);
    kind.push_back(k);
    body.push_back(body_id);
    id.push_back(next_id);
    n_active = pos.size();
  }

  // Calls fn(array) for every per-particle array, so reordering can never miss one.
  template <class Fn>
  void for_each_array(Fn&& fn) {
    fn(pos);
    fn(vel);
    fn(rho);
    fn(pos0);
    fn(vel0);
    fn(rho0);
    fn(mass);
    fn(kind);
    fn(body);
    fn(id);
  }

  // new[i] = old[order[i]] for every array. Scratch buffers are reused between calls. Two
  // parallel regions (gathers without barriers between them); serial for small sets. Two
  // vector scratch arrays serve the four vector arrays: pos0 and vel0 are gathered in the
  // second pass into the storage pos and vel left behind.
  void permute(const std::vector<std::uint32_t>& order) {
    const long n = static_cast<long>(order.size());
    const std::size_t total = pos.size();
    auto gather = [&](auto& a, auto& scratch) {
#pragma omp for schedule(static) nowait
      for (long i = 0; i < n; ++i) scratch[i] = a[order[i]];
    };
    auto finish = [&](auto& a, auto& scratch) {
      for (std::size_t i = order.size(); i < total; ++i) scratch[i] = a[i];
      a.swap(scratch);
    };
    for (auto* s : {&scratch_v_[0], &scratch_v_[1]}) s->resize(total);
    for (auto* s : {&scratch_d_[0], &scratch_d_[1], &scratch_d_[2]}) s->resize(total);
    scratch_k_.resize(total);
    scratch_b_.resize(total);
    scratch_i_.resize(total);
#pragma omp parallel if (n > kParallelMin)
    {
      gather(pos, scratch_v_[0]);
      gather(vel, scratch_v_[1]);
      gather(rho, scratch_d_[0]);
      gather(rho0, scratch_d_[1]);
      gather(mass, scratch_d_[2]);
      gather(kind, scratch_k_);
      gather(body, scratch_b_);
      gather(id, scratch_i_);
    }
    finish(pos, scratch_v_[0]);
    finish(vel, scratch_v_[1]);
    finish(rho, scratch_d_[0]);
    finish(rho0, scratch_d_[1]);
    finish(mass, scratch_d_[2]);
    finish(kind, scratch_k_);
    finish(body, scratch_b_);
    finish(id, scratch_i_);
#pragma omp parallel if (n > kParallelMin)
    {
      gather(pos0, scratch_v_[0]);
      gather(vel0, scratch_v_[1]);
    }
    finish(pos0, scratch_v_[0]);
    finish(vel0, scratch_v_[1]);
  }

  // Below this many particles the O(N) loops of the sort run serially: their parallel
  // region would cost more than the loop.
  static constexpr long kParallelMin = 8192;

 private:
  std::vector<V> scratch_v_[2];
  std::vector<double> scratch_d_[3];
  std::vector<Kind> scratch_k_;
  std::vector<std::uint16_t> scratch_b_;
  std::vector<std::uint32_t> scratch_i_;
};

}  // namespace swell
