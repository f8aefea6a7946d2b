// Moving boundary bodies as a step hook: at every substep of either integrator (the prescribe
// stage) the particles of each moving body take the position and velocity of their body's
// motion law (bc/motion.hpp) at the substep time, from their body-frame reference position
// (the pos_ref field). The wall velocity then enters continuity, viscosity and the force on
// the fluid through the pair loop like any particle velocity. A pure function of time, so a
// restart moves the bodies exactly as the uninterrupted run; the checkpoint keeps each body's
// pose at the last prescribed time, and a restart from a case whose motion differs is refused.
// With mDBC the wall normals turn with the body (from their body-frame copy, normal_ref), and
// for mDBC's hydrostatic wall pressure each moving wall particle also gets its acceleration
// (wall_acc), the central difference (v(t + e) - v(t - e)) / 2e of its placed velocity, e = 1 ms
// (a jump in a law's velocity is spread over 2 ms rather than read as a spike).
#pragma once

#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bc/absorption.hpp"
#include "bc/motion.hpp"
#include "solver/state/particle_set.hpp"
#include "solver/time/step_hooks.hpp"

namespace swell {

template <int D>
class MovingBodies final : public StepHook<D> {
 public:
  // laws[b]: the motion of body b (body id = index; a default MotionLaw does not move).
  explicit MovingBodies(std::vector<MotionLaw> laws)
      : laws_(std::move(laws)),
        poses_(laws_.size()),
        placements_(laws_.size()),
        absorbers_(laws_.size()) {
    for (std::size_t b = 0; b < laws_.size(); ++b) {
      const MotionSpec& spec = laws_[b].spec();
      if (spec.type != MotionSpec::Type::Wave || !spec.absorption) continue;
      absorbers_[b].emplace(spec);
      absorbers_[b]->body_ = b;
    }
  }

  // The absorber of body b (bc/absorption.hpp), or null.
  const PaddleAbsorber* absorber(std::size_t b) const {
    return b < absorbers_.size() && absorbers_[b] ? &*absorbers_[b] : nullptr;
  }

  // Active absorption: the paddles measure the water in front of them once per step.
  void after_integration(StepState<D>& s) override {
    for (std::size_t b = 0; b < absorbers_.size(); ++b) {
      if (!absorbers_[b]) continue;
      const RigidPose law = laws_[b].pose(s.time);
      absorbers_[b]->update(s.particles, s.params, s.time, s.dt,
                            law.d.dot(laws_[b].spec().direction), s.exchange);
    }
  }

  std::string name() const override { return "motion"; }
  // Moves walls in prescribe (before the next halo build); the absorbers read owned particles.
  bool changes_state_before_forces() const override { return false; }
  bool reads_images_after_integration() const override { return false; }
  const std::vector<MotionLaw>& laws() const { return laws_; }

  static bool any_moves(const std::vector<MotionLaw>& laws) {
    for (const auto& l : laws)
      if (l.moves()) return true;
    return false;
  }

  // Before the run: wall particles of moving bodies become moving walls with their current
  // position as reference (pos_ref enabled), placed at their pose at t = 0; with
  // `accelerations`, the wall_acc field is enabled and kept.
  static void prepare(ParticleSet<D>& ps, const std::vector<MotionLaw>& laws,
                      bool accelerations = false) {
    if (!any_moves(laws)) return;
    for (std::size_t i = 0; i < ps.total(); ++i) {
      const auto b = ps.body[i];
      if (is_wall(ps.role[i]) && b < laws.size() && laws[b].moves()) ps.role[i] = Role::MovingWall;
    }
    ps.enable("pos_ref", ps.pos);
    // mDBC normals turn with their body: keep them in the body frame too.
    // (By the flag, not the size: a rank's share of a set-up may be empty.)
    if (ps.enabled("normal")) ps.enable("normal_ref", ps.normal);
    if (accelerations) ps.enable("wall_acc", std::vector<Vec<D>>(ps.total(), Vec<D>::Zero()));
    MovingBodies<D> m(laws);
    m.place_all(ps, 0.0);
  }

  void prescribe(StepState<D>& s) override { place_all(s.particles, s.time); }

  void save(std::map<std::string, double>& out) const override {
    out["time"] = t_last_;
    for (std::size_t b = 0; b < laws_.size(); ++b) {
      if (!laws_[b].moves()) continue;
      const std::string k = "body" + std::to_string(b) + ".";
      for (int d = 0; d < 3; ++d) out[k + "d" + std::to_string(d)] = poses_[b].d[d];
      out[k + "theta"] = poses_[b].theta;
      if (absorbers_[b]) absorbers_[b]->save(out, k);
    }
  }

  // The saved poses must be what this case's laws give at the saved time: otherwise the case's
  // motion was changed since the checkpoint and continuing would jump the bodies.
  void restore(const std::map<std::string, double>& in) override {
    const auto t = in.find("time");
    if (t == in.end()) {
      if (any_moves(laws_))
        throw std::invalid_argument(
            "checkpoint: it holds no motion state, but the case has moving bodies (was it "
            "written by a run of another case?)");
      return;
    }
    t_last_ = t->second;
    for (std::size_t b = 0; b < laws_.size(); ++b) {
      if (!laws_[b].moves()) continue;
      const std::string k = "body" + std::to_string(b) + ".";
      if (absorbers_[b] && !absorbers_[b]->restore(in, k))
        throw std::invalid_argument("checkpoint: no absorption state for body " +
                                    std::to_string(b) +
                                    ", whose paddle absorbs in the case (the case was changed)");
      poses_[b] = pose_at(b, t_last_);
      auto saved = [&](const std::string& key) {
        const auto it = in.find(k + key);
        if (it == in.end())
          throw std::invalid_argument("checkpoint: no motion state for body " + std::to_string(b) +
                                      ", which moves in the case (the case was changed)");
        return it->second;
      };
      double diff = std::abs(saved("theta") - poses_[b].theta);
      for (int d = 0; d < 3; ++d)
        diff = std::max(diff, std::abs(saved("d" + std::to_string(d)) - poses_[b].d[d]));
      if (!(diff <= 1e-12 * (1.0 + poses_[b].d.norm() + std::abs(poses_[b].theta))))
        throw std::invalid_argument(
            "checkpoint: body " + std::to_string(b) + "'s pose at t = " + std::to_string(t_last_) +
            " s differs from what the case's motion gives (the motion was changed since the "
            "checkpoint; restart needs the case the run was started with)");
    }
  }

 private:
  void place_all(ParticleSet<D>& ps, double t) {
    const bool acc = !ps.wall_acc.empty();
    if (acc && ahead_.size() < laws_.size())
      ahead_.resize(laws_.size()), behind_.resize(laws_.size());
    for (std::size_t b = 0; b < laws_.size(); ++b) {
      if (!laws_[b].moves()) continue;
      poses_[b] = pose_at(b, t);
      placements_[b] = laws_[b].placement(poses_[b]);
      if (!acc) continue;
      ahead_[b] = laws_[b].placement(pose_at(b, t + kAccStep));
      behind_[b] = laws_[b].placement(pose_at(b, t - kAccStep));
    }
    t_last_ = t;
    const long n = static_cast<long>(ps.size());
    const bool turn_normals = !ps.normal_ref.empty();
#pragma omp parallel for schedule(static) if (n > ParticleSet <D>::kParallelMin)
    for (long i = 0; i < n; ++i) {
      if (ps.role[i] != Role::MovingWall) continue;
      const auto b = ps.body[i];
      Eigen::Vector3d ref = Eigen::Vector3d::Zero(), x, v;
      ref.template head<D>() = ps.pos_ref[i];
      placements_[b].apply(ref, x, v);
      ps.pos[i] = x.template head<D>();
      ps.vel[i] = narrow<D>(Vec<D>(v.template head<D>()));
      if (acc) {
        Eigen::Vector3d xa, va, xb, vb;
        ahead_[b].apply(ref, xa, va);
        behind_[b].apply(ref, xb, vb);
        ps.wall_acc[i] = ((va - vb) / (2.0 * kAccStep)).template head<D>();
      }
      if (turn_normals) {
        Eigen::Vector3d nref = Eigen::Vector3d::Zero();
        nref.template head<D>() = ps.normal_ref[i];
        ps.normal[i] = (placements_[b].rotation * nref).template head<D>();
      }
    }
  }

  // The law's pose plus, for an absorbing paddle, its correction along `direction`.
  RigidPose pose_at(std::size_t b, double t) const {
    RigidPose p = laws_[b].pose(t);
    if (absorbers_[b]) {
      const Eigen::Vector3d& dir = laws_[b].spec().direction;
      p.d += absorbers_[b]->offset(t) * dir;
      p.dv += absorbers_[b]->velocity() * dir;
    }
    return p;
  }

  std::vector<MotionLaw> laws_;
  std::vector<RigidPose> poses_;
  std::vector<RigidPlacement> placements_;
  static constexpr double kAccStep = 1e-3;  // [s] for the walls' accelerations
  std::vector<RigidPlacement> ahead_, behind_;
  std::vector<std::optional<PaddleAbsorber>> absorbers_;
  double t_last_ = 0.0;
};

}  // namespace swell
