#pragma once
// The processes taking part in one `wrc generate` run, as far as the generator needs them:
// ranks, and non-blocking point-to-point messages of bytes. The MPI implementation lives in
// mpi_cluster.cpp, so nothing else in the generator depends on MPI.

#include <memory>
#include <string>

namespace wrc::gen {

/// Message tags of the generator's protocol (see generate.cpp).
enum MessageTag : int {
  kTagHello = 1,    ///< rank > 0 → 0: its scene fingerprint.
  kTagStart = 2,    ///< 0 → rank: empty to go ahead, else the error that stops the run.
  kTagRequest = 3,  ///< rank → 0: wants up to n more lines.
  kTagTasks = 4,    ///< 0 → rank: lines (EncodeTasks); none means no more work.
  kTagRecords = 5,  ///< rank → 0: finished points (journal records).
  kTagStop = 6,     ///< 0 → rank: stop after the current point (interrupted).
  kTagDone = 7,     ///< rank → 0: all its workers finished, all its records sent.
};

class Cluster {
 public:
  virtual ~Cluster() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Ranks running on this machine (for sharing out its cores).
  virtual int local_size() const = 0;
  /// Sends bytes without blocking; the cluster keeps them until delivered. Only the thread
  /// that created the cluster may call Send and Receive.
  virtual void Send(int destination, int tag, std::string bytes) = 0;
  /// Receives one waiting message, if any (non-blocking).
  virtual bool Receive(int* source, int* tag, std::string* bytes) = 0;
  /// Blocks until every message sent so far has been delivered.
  virtual void CompleteSends() = 0;
};

/// Whether the environment says this process was started by mpirun/mpiexec with more than one
/// rank (Open MPI, MPICH/Hydra, PMIx launchers set such variables).
bool LaunchedWithSeveralRanks();

/// Joins MPI (MPI_Init_thread, funneled) when launched with several ranks and MPI support was
/// built; nullptr otherwise. Throws InputError when launched with several ranks but built
/// without MPI (each process would otherwise compute the whole table).
std::unique_ptr<Cluster> JoinClusterIfLaunched();

/// True when this build has MPI support.
bool ClusterSupportAvailable();

}  // namespace wrc::gen
