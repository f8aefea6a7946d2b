// The communicator the domain decomposition talks through (issue #16): MPI_COMM_WORLD in a
// build with MPI under `mpirun`, a single rank otherwise (the serial build behaves as before:
// every collective is the identity). Only what the decomposition needs: rank and size,
// reductions (the global time step, counts, sums) and one all-to-all of byte buffers (halo and
// migration traffic). The buffers are owned by the caller and reused, so a steady exchange
// allocates nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace swell::parallel {

class Comm {
 public:
  // The world communicator (MPI_COMM_WORLD when MPI is built in and initialised, else one
  // rank).
  static Comm world();
  // A single-rank communicator, whatever the build.
  static Comm self() { return Comm(); }

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool serial() const { return size_ == 1; }

  double min(double x) const;
  double max(double x) const;
  double sum(double x) const;
  std::uint64_t sum(std::uint64_t x) const;
  // Element-wise sum over ranks of a vector of counts (same length everywhere).
  void sum_in_place(std::vector<std::uint64_t>& v) const;
  void sum_in_place(std::vector<double>& v) const;
  // Element-wise maximum over ranks, in place.
  void max_in_place(std::vector<double>& v) const;
  // Element-wise sum over the ranks below this one (rank 0 gets zeros), in place.
  void exscan_in_place(std::vector<std::uint64_t>& v) const;
  // The ranks on this rank's node (sharing its memory), this one included.
  int node_size() const;
  // The message of the lowest rank whose `mine` is not empty, on every rank ("" if none): an
  // agreement on whether a local step failed anywhere, with the reason.
  std::string first_message(const std::string& mine) const;
  // Every rank's value, in rank order.
  std::vector<std::uint64_t> gather_all(std::uint64_t x) const;
  void gather_all(std::uint64_t x, std::vector<std::uint64_t>& all) const;  // into `all`

  // All-to-all of bytes: send[send_displ[r], send_displ[r] + send_count[r]) goes to rank r;
  // recv is resized to hold what arrives, rank r's part at recv_displ[r] (count recv_count[r]).
  // Counts are in bytes (and must fit an int, as MPI needs).
  void alltoallv(const std::vector<std::byte>& send, const std::vector<int>& send_count,
                 std::vector<std::byte>& recv, std::vector<int>& recv_count,
                 std::vector<int>& recv_displ) const;

  // Neighbour exchange along a line of ranks (the slabs): sends [lo, lo + lo_bytes) to rank - 1
  // and [hi, hi + hi_bytes) to rank + 1 (nothing where there is no such rank), and receives
  // what rank - 1 and rank + 1 send this way, in that order, into recv (resized to hold both;
  // recv_lo_bytes: the part from rank - 1). Sizes travel first. Point-to-point: its latency
  // does not grow with the number of ranks, unlike alltoallv's. `ring`: the line is closed
  // (slabs along a periodic axis): rank 0's rank - 1 is the last rank and the last rank's
  // rank + 1 is rank 0 (on 2 ranks both are the other rank; the tags keep the two apart).
  void neighbour_exchange(const std::byte* lo, std::size_t lo_bytes, const std::byte* hi,
                          std::size_t hi_bytes, std::vector<std::byte>& recv,
                          std::size_t& recv_lo_bytes, bool ring = false) const;

  void barrier() const;

 private:
  Comm() = default;
  int rank_ = 0, size_ = 1;
  bool mpi_ = false;
};

// MPI_Init_thread (FUNNELED: OpenMP threads inside a rank, MPI calls from the master thread)
// for the lifetime of this object; MPI_Finalize at its end. It initialises MPI only in a
// process started by mpirun / mpiexec (their OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK in
// the environment): a plain `swell ...` never starts MPI (no singleton start-up, no network
// probing). Without MPI in the build, or when MPI is already initialised, it does nothing.
class Environment {
 public:
  Environment(int& argc, char**& argv);
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

 private:
  bool owner_ = false;
};

// Whether this build has MPI.
bool have_mpi();
// Whether this process was started by an MPI launcher (see Environment).
bool launched_by_mpirun();
// The number of ranks the launcher started (OMPI_COMM_WORLD_SIZE or PMI_SIZE), 1 without
// one: known without MPI, so a single-rank build can refuse a multi-rank launch.
int launcher_world_size();

}  // namespace swell::parallel
