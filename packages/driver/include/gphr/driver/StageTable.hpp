#pragma once
/// @file
/// `gphr build`'s per-stage clocks of every rank (StageClock.hpp) as DIR/stages.csv, their time
/// inside MPI per MPI function as DIR/mpi_calls.csv, and a short table on the console
/// (doc/reference.md, "stages.csv"; bench/scaling.sh reads both files).
#include <string>
#include <vector>

#include "gphr/core/StageClock.hpp"
#include "gphr/core/Types.hpp"

namespace gphr {

/// Every rank's stages, gathered: row r * stages + s is rank r's stage s.
struct StageTable {
  std::vector<std::string> names;  ///< the stages, in order (rank 0's; every rank has the same)
  int ranks = 0;                   ///< the communicator's size
  std::vector<StageTime> rows;     ///< rank-major
  /// The CSV text: rank,stage,wall_s,cpu_s,mpi_wall_s,mpi_cpu_s,compute_s,peak_rss_mb,critical_s.
  std::string csv() const;
  /// The CSV text rank,stage,call,calls,wall_s: per rank and stage each MPI function it called
  /// (mpi_wall_s split by function; empty without the PMPI interposer).
  std::string mpiCallsCsv() const;
  /// One line per stage: max over ranks of wall and compute seconds, and of peak memory.
  std::string summary() const;
};

/// Gathers every rank's `stages` (collective; the ranks ran the same stages, checked: an
/// std::logic_error otherwise, as a program error).
StageTable gatherStages(const RCP<const Comm>& comm, const std::vector<StageTime>& stages);

}  // namespace gphr
