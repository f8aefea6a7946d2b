// A restart's reading of its checkpoint: that it continues the same case, and which rows of
// the file this rank reads.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "io/hdf5_file.hpp"
#include "parallel/comm.hpp"

namespace swell {

// A restart continues the case its checkpoint was written by (the case identity: text, --set
// edits, input files, all but time.end). Every rank checks, so every rank refuses alike.
void check_checkpoint_case(const std::string& ck, const CaseTag& saved, const CaseTag& tag,
                           const std::string& case_file);

// A restart on as many ranks as wrote the checkpoint: this rank's place in it (every rank's
// counts from its decomposition record), so it reads only its own rows; none otherwise.
std::optional<WriteShare> restart_rows(const std::map<std::string, double>& saved,
                                       const parallel::Comm& comm);

// How this rank reads a checkpoint at a restart: on as many ranks as wrote it, its own rows
// (restart_rows); on another number of ranks after a set-up in shares, a block of the active
// rows (rank 0 also every excluded row), whose particles then go to their slabs
// (build_simulation); otherwise (one rank, SWELL_WHOLE_SETUP=1) the whole file. No
// collective: every rank decides alike from the same file and set-up.
struct RestartRead {
  std::optional<WriteShare> rows;
  bool blocks = false;
  std::uint64_t first_row = 0;  // blocks: the file row of this rank's first active particle
};
RestartRead restart_read(const std::string& ck, const parallel::Comm& comm, bool distributed);

}  // namespace swell
