// MPI behind the Cluster interface. Built with MPI when CMake found it (WRC_HAVE_MPI); without
// it, JoinClusterIfLaunched() only checks that the process was not meant to be one of several.

#include <cstdlib>
#include <cstring>
#include <string>

#include "generator/cluster.h"
#include "wrc/core/errors.h"

#ifdef WRC_HAVE_MPI
// The C API only: Open MPI's and MPICH's mpi.h otherwise pull in the deprecated C++ bindings,
// which need libmpi_cxx.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <iterator>
#include <list>
#include <stdexcept>
#endif

namespace wrc::gen {
namespace {

// The number of ranks the launcher announced, 0 when not known.
long AnnouncedSize() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {  // Open MPI, MPICH (Hydra)
    if (const char* value = std::getenv(name)) return std::strtol(value, nullptr, 10);
  }
  return 0;
}

}  // namespace

bool LaunchedWithSeveralRanks() {
  const long size = AnnouncedSize();
  if (size > 1) return true;
  // PMIx launchers (srun --mpi=pmix) may announce only the rank.
  return size == 0 && std::getenv("PMIX_RANK") != nullptr;
}

#ifdef WRC_HAVE_MPI

namespace {

// A failing MPI call is the launch's or the installation's (a rank that died, a library without
// thread support), the user's to fix like any other environment: InputError.
void CheckMpi(int code, const char* what) {
  if (code != MPI_SUCCESS) {
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw InputError(std::string("MPI: ") + what + ": " + std::string(text, length));
  }
}

class MpiCluster : public Cluster {
 public:
  MpiCluster() {
    int provided = MPI_THREAD_SINGLE;
    CheckMpi(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "init");
    // Worker threads never call MPI; the main thread does all communication, which is what
    // MPI_THREAD_FUNNELED promises. SINGLE would formally forbid other threads to exist.
    if (provided < MPI_THREAD_FUNNELED) {
      MPI_Finalize();
      throw InputError("MPI: the library does not support MPI_THREAD_FUNNELED");
    }
    // Return errors instead of aborting, so that they reach the user as messages.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    CheckMpi(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "rank");
    CheckMpi(MPI_Comm_size(MPI_COMM_WORLD, &size_), "size");
    MPI_Comm local;
    CheckMpi(
        MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local),
        "split by machine");
    CheckMpi(MPI_Comm_size(local, &local_size_), "local size");
    MPI_Comm_free(&local);
  }

  ~MpiCluster() override {
    try {
      CompleteSends();
    } catch (...) {
      // Finalizing anyway: a failed delivery was already reported by the protocol.
    }
    MPI_Finalize();
  }

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int local_size() const override { return local_size_; }

  void Send(int destination, int tag, std::string bytes) override {
    pending_.push_back(Pending{std::move(bytes), MPI_REQUEST_NULL});
    Pending& message = pending_.back();
    CheckMpi(MPI_Isend(message.bytes.data(), static_cast<int>(message.bytes.size()), MPI_BYTE,
                       destination, tag, MPI_COMM_WORLD, &message.request),
             "send");
    ReapSends();
  }

  bool Receive(int* source, int* tag, std::string* bytes) override {
    ReapSends();
    int waiting = 0;
    MPI_Status status;
    CheckMpi(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status), "probe");
    if (!waiting) return false;
    int count = 0;
    CheckMpi(MPI_Get_count(&status, MPI_BYTE, &count), "message size");
    bytes->assign(static_cast<std::size_t>(count), '\0');
    CheckMpi(MPI_Recv(bytes->data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG,
                      MPI_COMM_WORLD, MPI_STATUS_IGNORE),
             "receive");
    *source = status.MPI_SOURCE;
    *tag = status.MPI_TAG;
    return true;
  }

  void CompleteSends() override {
    for (Pending& message : pending_) {
      CheckMpi(MPI_Wait(&message.request, MPI_STATUS_IGNORE), "complete a send");
    }
    pending_.clear();
  }

 private:
  struct Pending {
    std::string bytes;  // owned until MPI has sent it
    MPI_Request request;
  };

  // Frees the buffers of sends that completed.
  void ReapSends() {
    for (auto it = pending_.begin(); it != pending_.end();) {
      int done = 0;
      CheckMpi(MPI_Test(&it->request, &done, MPI_STATUS_IGNORE), "test a send");
      it = done ? pending_.erase(it) : std::next(it);
    }
  }

  int rank_ = 0, size_ = 1, local_size_ = 1;
  std::list<Pending> pending_;  // a list: buffers must not move while MPI reads them
};

}  // namespace

std::unique_ptr<Cluster> JoinClusterIfLaunched() {
  if (!LaunchedWithSeveralRanks()) return nullptr;
  return std::make_unique<MpiCluster>();
}

bool ClusterSupportAvailable() { return true; }

#else

std::unique_ptr<Cluster> JoinClusterIfLaunched() {
  if (LaunchedWithSeveralRanks()) {
    throw InputError(
        "wrc generate was started as one of several MPI ranks, but this wrc was built without "
        "MPI support; install Open MPI (tools/setup.sh) and rebuild, or run without mpirun");
  }
  return nullptr;
}

bool ClusterSupportAvailable() { return false; }

#endif

}  // namespace wrc::gen
