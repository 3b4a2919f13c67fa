// The team of an MPI job (`mpirun -np N motiongraph build ...`, `srun motiongraph build ...`):
// a parallel/process_team.h ProcessTeam over MPI_COMM_WORLD, built only when CMake finds MPI
// (Open MPI: Debian's libopenmpi-dev and openmpi-bin). MPI is started when the team is made and
// finished when it goes; only the main thread calls MPI (MPI_THREAD_FUNNELED). MPI's errors are
// fatal (its default). Made only when launched_by_mpi() (parallel/process_team.h): a plain run
// never starts MPI: a process that dies or cannot be reached ends the whole job through the
// launcher, and no process writes its outputs before every process has handed its tiles over.
#pragma once

#include "motiongraph/parallel/process_team.h"

namespace mg {

class MpiTeam final : public ProcessTeam {
 public:
  MpiTeam();
  ~MpiTeam() override;
  MpiTeam(const MpiTeam&) = delete;
  MpiTeam& operator=(const MpiTeam&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  bool broadcast(bool value) override;
  std::vector<std::string> gather(const std::string& bytes) override;

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace mg
