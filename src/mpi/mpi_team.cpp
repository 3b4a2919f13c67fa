#include "mpi/mpi_team.h"

#include <mpi.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <algorithm>

namespace mg {

namespace {

// MPI counts are ints: large messages go as pieces of at most 1 GiB, by point-to-point sends.
constexpr long long kPiece = 1LL << 30;

void send_bytes(const std::string& bytes, int to) {
  for (long long at = 0; at < static_cast<long long>(bytes.size()); at += kPiece) {
    const int count = static_cast<int>(std::min<long long>(kPiece, static_cast<long long>(bytes.size()) - at));
    MPI_Send(bytes.data() + at, count, MPI_BYTE, to, 1, MPI_COMM_WORLD);
  }
}

void receive_bytes(std::string& bytes, int from) {
  for (long long at = 0; at < static_cast<long long>(bytes.size()); at += kPiece) {
    const int count = static_cast<int>(std::min<long long>(kPiece, static_cast<long long>(bytes.size()) - at));
    MPI_Recv(bytes.data() + at, count, MPI_BYTE, from, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
}

// When a process of the job fails or dies, the launcher stops the others with SIGTERM: rank 0
// says so in one line (the launcher's own account is silenced by mpirun -q) and leaves at once,
// before writing anything. Only async-signal-safe calls here.
void stopped_by_launcher(int) {
  static const char kLine[] =
      "motiongraph: error: the MPI job was stopped (a process failed, was killed or was interrupted): no graph "
      "written\n";
  const ssize_t written = write(STDERR_FILENO, kLine, sizeof kLine - 1);
  static_cast<void>(written);
  _exit(1);
}

void quiet_exit(int) { _exit(1); }

}  // namespace

MpiTeam::MpiTeam() {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  std::signal(SIGTERM, rank_ == 0 ? stopped_by_launcher : quiet_exit);
}

MpiTeam::~MpiTeam() {
  // The build has said how it ended: a late stop needs no second word.
  std::signal(SIGTERM, quiet_exit);
  MPI_Finalize();
}

bool MpiTeam::broadcast(bool value) {
  int flag = value ? 1 : 0;
  MPI_Bcast(&flag, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return flag != 0;
}

std::vector<std::string> MpiTeam::gather(const std::string& bytes) {
  long long size = static_cast<long long>(bytes.size());
  std::vector<long long> sizes(rank_ == 0 ? static_cast<size_t>(size_) : 0);
  MPI_Gather(&size, 1, MPI_LONG_LONG, sizes.data(), 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  if (rank_ != 0) {
    send_bytes(bytes, 0);
    return {};
  }
  std::vector<std::string> all(static_cast<size_t>(size_));
  all[0] = bytes;
  for (int r = 1; r < size_; ++r) {
    all[static_cast<size_t>(r)].resize(static_cast<size_t>(sizes[static_cast<size_t>(r)]));
    receive_bytes(all[static_cast<size_t>(r)], r);
  }
  return all;
}

}  // namespace mg
