#include "run/restart.hpp"

#include <stdexcept>

namespace swell {

// A restart continues the case its checkpoint was written by (the case identity: text, --set
// edits, input files, all but time.end). Every rank checks, so every rank refuses alike.
void check_checkpoint_case(const std::string& ck, const CaseTag& saved, const CaseTag& tag,
                           const std::string& case_file) {
  if (saved.identity.empty())
    throw std::invalid_argument(
        ck +
        " does not say which case wrote it (a checkpoint of an older Swell): restart "
        "needs a checkpoint written by this version; run the case afresh with --overwrite");
  if (saved.identity != tag.identity)
    throw std::invalid_argument(
        ck + " was written by case '" + saved.name + "' (" + saved.file + "), and " + case_file +
        " differs from it (case text, --set edits or an input file, other than time.end; case "
        "identity " +
        tag.identity.substr(0, 12) + " against " + saved.identity.substr(0, 12) +
        "): a restart continues the case the run was started with; run this one with "
        "--overwrite or -o another folder");
}

// A restart on as many ranks as wrote the checkpoint: this rank's place in it (every rank's
// counts from its decomposition record), so it reads only its own rows; none otherwise.
std::optional<WriteShare> restart_rows(const std::map<std::string, double>& saved,
                                       const parallel::Comm& comm) {
  const auto ranks = saved.find("decomposition.ranks");
  if (comm.size() == 1 || ranks == saved.end() || static_cast<int>(ranks->second) != comm.size())
    return std::nullopt;
  WriteShare w;
  w.rank = comm.rank();
  for (int r = 0; r < comm.size(); ++r) {
    const auto a = saved.find("decomposition.active." + std::to_string(r));
    const auto e = saved.find("decomposition.excluded." + std::to_string(r));
    if (a == saved.end() || e == saved.end()) return std::nullopt;  // read it whole instead
    w.active.push_back(static_cast<std::uint64_t>(a->second));
    w.excluded.push_back(static_cast<std::uint64_t>(e->second));
  }
  return w;
}

// How this rank reads a checkpoint at a restart: on as many ranks as wrote it, its own rows
// (restart_rows); on another number of ranks after a set-up in shares, a block of the active
// rows (rank 0 also every excluded row), whose particles then go to their slabs
// (build_simulation); otherwise (one rank, SWELL_WHOLE_SETUP=1) the whole file. No
// collective: every rank decides alike from the same file and set-up.

RestartRead restart_read(const std::string& ck, const parallel::Comm& comm, bool distributed) {
  RestartRead r;
  r.rows = restart_rows(read_checkpoint_schedule(ck), comm);
  if (r.rows || comm.size() == 1 || !distributed) return r;
  const auto [active, total] = checkpoint_counts(ck);
  const auto n = static_cast<std::uint64_t>(comm.size());
  WriteShare w;
  w.rank = comm.rank();
  for (std::uint64_t k = 0; k < n; ++k) {
    const std::uint64_t a = active * k / n, b = active * (k + 1) / n;
    if (static_cast<int>(k) == comm.rank()) r.first_row = a;
    w.active.push_back(b - a);
    w.excluded.push_back(k == 0 ? total - active : 0);
  }
  r.rows = w;
  r.blocks = true;
  return r;
}

}  // namespace swell
