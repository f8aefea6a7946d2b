#include "parallel/comm.hpp"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <string>

#ifdef SWELL_HAVE_MPI
#include <mpi.h>
#endif

namespace swell::parallel {

bool have_mpi() {
#ifdef SWELL_HAVE_MPI
  return true;
#else
  return false;
#endif
}

bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

int launcher_world_size() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* s = std::getenv(v)) {
      const int n = std::atoi(s);
      if (n > 0) return n;
    }
  return 1;
}

Comm Comm::world() {
  Comm c;
#ifdef SWELL_HAVE_MPI
  int init = 0, fin = 0;
  MPI_Initialized(&init);
  MPI_Finalized(&fin);
  if (init && !fin) {
    MPI_Comm_rank(MPI_COMM_WORLD, &c.rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &c.size_);
    c.mpi_ = true;
  }
#endif
  return c;
}

#ifdef SWELL_HAVE_MPI
namespace {
template <class T>
T reduce(T x, MPI_Datatype type, MPI_Op op) {
  T y{};
  MPI_Allreduce(&x, &y, 1, type, op, MPI_COMM_WORLD);
  return y;
}
}  // namespace
#endif

double Comm::min(double x) const {
#ifdef SWELL_HAVE_MPI
  if (mpi_) return reduce(x, MPI_DOUBLE, MPI_MIN);
#endif
  return x;
}
double Comm::max(double x) const {
#ifdef SWELL_HAVE_MPI
  if (mpi_) return reduce(x, MPI_DOUBLE, MPI_MAX);
#endif
  return x;
}
double Comm::sum(double x) const {
#ifdef SWELL_HAVE_MPI
  if (mpi_) return reduce(x, MPI_DOUBLE, MPI_SUM);
#endif
  return x;
}
std::uint64_t Comm::sum(std::uint64_t x) const {
#ifdef SWELL_HAVE_MPI
  if (mpi_) return reduce(x, MPI_UINT64_T, MPI_SUM);
#endif
  return x;
}

#ifdef SWELL_HAVE_MPI
namespace {
// Element-wise sum over the ranks, in place.
template <class T>
void sum_vector(std::vector<T>& v, MPI_Datatype type) {
  if (!v.empty())
    MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), type, MPI_SUM,
                  MPI_COMM_WORLD);
}
}  // namespace
#endif

void Comm::sum_in_place(std::vector<std::uint64_t>& v) const {
#ifdef SWELL_HAVE_MPI
  if (mpi_) sum_vector(v, MPI_UINT64_T);
#endif
  (void)v;
}

void Comm::sum_in_place(std::vector<double>& v) const {
#ifdef SWELL_HAVE_MPI
  if (mpi_) sum_vector(v, MPI_DOUBLE);
#endif
  (void)v;
}

void Comm::max_in_place(std::vector<double>& v) const {
#ifdef SWELL_HAVE_MPI
  if (mpi_ && !v.empty())
    MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_MAX,
                  MPI_COMM_WORLD);
#endif
  (void)v;
}

void Comm::exscan_in_place(std::vector<std::uint64_t>& v) const {
#ifdef SWELL_HAVE_MPI
  if (mpi_ && size_ > 1 && !v.empty()) {
    std::vector<std::uint64_t> below(v.size(), 0);
    MPI_Exscan(v.data(), below.data(), static_cast<int>(v.size()), MPI_UINT64_T, MPI_SUM,
               MPI_COMM_WORLD);
    if (rank_ == 0) below.assign(v.size(), 0);  // MPI leaves rank 0's result undefined
    v.swap(below);
    return;
  }
#endif
  v.assign(v.size(), 0);
}

int Comm::node_size() const {
#ifdef SWELL_HAVE_MPI
  if (mpi_ && size_ > 1) {
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
    int n = 1;
    MPI_Comm_size(node, &n);
    MPI_Comm_free(&node);
    return n;
  }
#endif
  return 1;
}

std::string Comm::first_message(const std::string& mine) const {
  if (!mpi_ || size_ == 1) return mine;
  std::string out;
#ifdef SWELL_HAVE_MPI
  const auto lengths = gather_all(static_cast<std::uint64_t>(mine.size()));
  int from = -1;
  for (int r = 0; r < size_ && from < 0; ++r)
    if (lengths[static_cast<std::size_t>(r)] > 0) from = r;
  if (from < 0) return out;
  out = rank_ == from ? mine : std::string(lengths[static_cast<std::size_t>(from)], ' ');
  MPI_Bcast(out.data(), static_cast<int>(out.size()), MPI_CHAR, from, MPI_COMM_WORLD);
#endif
  return out;
}

std::vector<std::uint64_t> Comm::gather_all(std::uint64_t x) const {
  std::vector<std::uint64_t> all;
  gather_all(x, all);
  return all;
}

void Comm::gather_all(std::uint64_t x, std::vector<std::uint64_t>& all) const {
  all.assign(static_cast<std::size_t>(size_), x);
#ifdef SWELL_HAVE_MPI
  if (mpi_) MPI_Allgather(&x, 1, MPI_UINT64_T, all.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
#endif
}

void Comm::alltoallv(const std::vector<std::byte>& send, const std::vector<int>& send_count,
                     std::vector<std::byte>& recv, std::vector<int>& recv_count,
                     std::vector<int>& recv_displ) const {
  const auto n = static_cast<std::size_t>(size_);
  if (send_count.size() != n) throw std::invalid_argument("Comm::alltoallv: one count per rank");
  recv_count.resize(n);
  recv_displ.resize(n);
  if (!mpi_) {
    recv_count[0] = send_count[0];
    recv_displ[0] = 0;
    recv.assign(send.begin(), send.begin() + send_count[0]);
    return;
  }
#ifdef SWELL_HAVE_MPI
  // Displacements: the send buffer holds the ranks' parts in rank order.
  thread_local std::vector<int> send_displ;
  send_displ.resize(n);
  std::exclusive_scan(send_count.begin(), send_count.end(), send_displ.begin(), 0);
  MPI_Alltoall(send_count.data(), 1, MPI_INT, recv_count.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::exclusive_scan(recv_count.begin(), recv_count.end(), recv_displ.begin(), 0);
  const std::size_t total =
      static_cast<std::size_t>(recv_displ.back()) + static_cast<std::size_t>(recv_count.back());
  if (recv.size() < total) recv.resize(total);
  MPI_Alltoallv(send.data(), send_count.data(), send_displ.data(), MPI_BYTE, recv.data(),
                recv_count.data(), recv_displ.data(), MPI_BYTE, MPI_COMM_WORLD);
#endif
}

void Comm::neighbour_exchange(const std::byte* lo, std::size_t lo_bytes, const std::byte* hi,
                              std::size_t hi_bytes, std::vector<std::byte>& recv,
                              std::size_t& recv_lo_bytes, bool ring) const {
  recv_lo_bytes = 0;
  if (ring && size_ == 1) {
    // A ring of one: what goes up comes back from below, what goes down from above.
    recv.resize(hi_bytes + lo_bytes);
    if (hi_bytes) std::memcpy(recv.data(), hi, hi_bytes);
    if (lo_bytes) std::memcpy(recv.data() + hi_bytes, lo, lo_bytes);
    recv_lo_bytes = hi_bytes;
    return;
  }
  if (!mpi_ || size_ == 1) {
    recv.clear();
    return;
  }
#ifdef SWELL_HAVE_MPI
  const int below = ring ? (rank_ + size_ - 1) % size_ : rank_ - 1,
            above = ring ? (rank_ + 1) % size_ : rank_ + 1;
  const bool has_below = below >= 0, has_above = above < size_;
  // Sizes first (as 64-bit counts), then the bytes; tags keep the two directions apart.
  std::uint64_t out_lo = lo_bytes, out_hi = hi_bytes, in_lo = 0, in_hi = 0;
  MPI_Request req[4];
  int nreq = 0;
  if (has_below) {
    MPI_Irecv(&in_lo, 1, MPI_UINT64_T, below, 1, MPI_COMM_WORLD, &req[nreq++]);
    MPI_Isend(&out_lo, 1, MPI_UINT64_T, below, 2, MPI_COMM_WORLD, &req[nreq++]);
  }
  if (has_above) {
    MPI_Irecv(&in_hi, 1, MPI_UINT64_T, above, 2, MPI_COMM_WORLD, &req[nreq++]);
    MPI_Isend(&out_hi, 1, MPI_UINT64_T, above, 1, MPI_COMM_WORLD, &req[nreq++]);
  }
  MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
  // Each message is checked by its sender and its receiver alike (both see the same count),
  // so the two ranks of a message both stop rather than one waiting for the other.
  constexpr auto kMax = static_cast<std::uint64_t>(INT32_MAX);
  if (in_lo > kMax || in_hi > kMax || out_lo > kMax || out_hi > kMax)
    throw std::runtime_error("Comm::neighbour_exchange: over 2 GiB in one message");
  if (recv.size() < in_lo + in_hi) recv.resize(in_lo + in_hi);
  nreq = 0;
  if (has_below) {
    MPI_Irecv(recv.data(), static_cast<int>(in_lo), MPI_BYTE, below, 3, MPI_COMM_WORLD,
              &req[nreq++]);
    MPI_Isend(lo, static_cast<int>(lo_bytes), MPI_BYTE, below, 4, MPI_COMM_WORLD, &req[nreq++]);
  }
  if (has_above) {
    MPI_Irecv(recv.data() + in_lo, static_cast<int>(in_hi), MPI_BYTE, above, 4, MPI_COMM_WORLD,
              &req[nreq++]);
    MPI_Isend(hi, static_cast<int>(hi_bytes), MPI_BYTE, above, 3, MPI_COMM_WORLD, &req[nreq++]);
  }
  MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
  recv_lo_bytes = in_lo;
  recv.resize(in_lo + in_hi);
#else
  (void)lo;
  (void)lo_bytes;
  (void)hi;
  (void)hi_bytes;
  (void)ring;
#endif
}

void Comm::barrier() const {
#ifdef SWELL_HAVE_MPI
  if (mpi_) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

Environment::Environment(int& argc, char**& argv) {
#ifdef SWELL_HAVE_MPI
  int init = 0;
  MPI_Initialized(&init);
  if (!init && launched_by_mpirun()) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    owner_ = true;
  }
#else
  (void)argc;
  (void)argv;
#endif
}

Environment::~Environment() {
#ifdef SWELL_HAVE_MPI
  if (owner_) MPI_Finalize();
#endif
}

}  // namespace swell::parallel
