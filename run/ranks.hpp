// A run on several ranks: each rank's simulation (its slab of the particles and the exchange
// with its neighbours), the decomposition's figures for the summary, and whether the ranks write
// their own rows of the shared output files.
#pragma once

#include <map>
#include <string>

#include "case/setup.hpp"
#include "parallel/comm.hpp"
#include "run/restart.hpp"

namespace swell {

// This rank's simulation. One rank: the case's, as always. Several: this rank's slab of the
// particles (`all`: the set-up's or a checkpoint's) with a SlabExchange. A checkpoint written
// on the same number of ranks (`saved` has its decomposition) gives each rank back exactly the
// particles it held, in their order, and the slab bounds; otherwise the slabs are balanced by
// fluid particle count along the domain's longest axis.
// `read`: how a restart read the checkpoint (`all` is then this rank's rows or block).
template <int D>
Simulation<D> build_simulation(const CaseSetup<D>& setup, ParticleSet<D> all,
                               const std::map<std::string, double>* saved,
                               const parallel::Comm& comm, long rebalance_every,
                               const RestartRead* read = nullptr);

// The decomposition's figures for the run summary (collective; every rank calls it after the
// loop, rank 0 gets the text): halo images and bytes per step per rank, migration, the time
// in the exchange (communication and packing) against the loop, and the balance now.
template <int D>
std::string decomposition_report(const Simulation<D>& sim, const parallel::Comm& comm,
                                 double loop_seconds, long loop_steps);

// SWELL_GATHER_OUTPUT=1: every output of a decomposed run from the whole state gathered to
// rank 0, as before parallel output (the tests compare the two, bit for bit).
bool gather_everything();

// Whether the ranks write their own particles into snapshots and checkpoints (parallel HDF5),
// else rank 0 writes them from a gather.
// Collective: every rank gets the same answer (the environment may differ between nodes).
bool use_shared_output(const parallel::Comm& comm);

}  // namespace swell
