// The case set-up of one rank of a decomposed run (issue #16): setup_case with its reductions
// over parallel::Comm (case/ does not link the MPI build of parallel/; run/ does).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "case/setup.hpp"
#include "parallel/comm.hpp"

namespace swell {

// The set-up's reductions over the ranks of a decomposed run (case/ does not link MPI).
class RankSetupReduce final : public SetupReduce {
 public:
  explicit RankSetupReduce(const parallel::Comm& comm) : comm_(comm), node_(comm.node_size()) {}
  int rank() const override { return comm_.rank(); }
  int size() const override { return comm_.size(); }
  int node_size() const override { return node_; }
  void sum(std::vector<double>& v) const override { comm_.sum_in_place(v); }
  void sum(std::vector<std::uint64_t>& v) const override { comm_.sum_in_place(v); }
  void max(std::vector<double>& v) const override { comm_.max_in_place(v); }
  void exscan(std::vector<std::uint64_t>& v) const override { comm_.exscan_in_place(v); }
  std::string first_message(const std::string& mine) const override {
    return comm_.first_message(mine);
  }

 private:
  parallel::Comm comm_;
  int node_;
};

// This rank's set-up (collective on several ranks: each fills its share of the case, see
// setup_case). SWELL_WHOLE_SETUP=1 on any rank: every rank sets up the whole case (and a
// restart then reads the whole checkpoint on every rank: CaseSetup::distributed is false), as
// before the distributed set-up (the tests compare the two, bit for bit).
template <int D>
inline CaseSetup<D> rank_setup(const CaseSpec& spec, const parallel::Comm& comm) {
  if (comm.size() == 1) return setup_case<D>(spec);
  const char* w = std::getenv("SWELL_WHOLE_SETUP");
  if (comm.max(w && std::string(w) == "1" ? 1.0 : 0.0) == 1.0) return setup_case<D>(spec);
  return setup_case<D>(spec, RankSetupReduce(comm));
}

}  // namespace swell
