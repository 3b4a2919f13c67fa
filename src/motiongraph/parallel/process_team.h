// The processes that share a build's distance stage (DESIGN.md 3.4: tiles are independent, so
// they spread over processes as over threads). Rank 0 selects, prunes and writes; the others
// compute their tiles and hand them over. ProcessTeam is what the pipeline talks to; OneProcess
// is the team of a plain run, and the MPI team (src/mpi/, built when CMake finds MPI) the one
// of `mpirun -np N motiongraph build ...`. Every process calls the same methods in the same
// order (they are collective).
//
// A process that dies ends the whole job (the MPI team's runtime sees to that); errors that a
// process returns reach rank 0 through agree() and gather(), which every process then fails on.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"

namespace mg {

class ProcessTeam {
 public:
  virtual ~ProcessTeam() = default;

  virtual int rank() const = 0;  // 0 .. size() - 1; 0 writes
  virtual int size() const = 0;
  // Rank 0's value, on every process.
  virtual bool broadcast(bool value) = 0;
  // Every process's bytes at rank 0, in rank order; empty on the others.
  virtual std::vector<std::string> gather(const std::string& bytes) = 0;

  // Ok on every process when every process's `local` is Ok. Else rank 0 gets the first failed
  // process's error (its message prefixed "process R: " when R is not 0) and the others an
  // ErrorKind::kOtherProcess error (rank 0 tells the user).
  Status agree(const Status& local);
};

// Whether an MPI launcher (mpirun, mpiexec, srun with PMI or PMIx) started this process, by
// the environment it sets; and how many processes it says the job has (0: it does not say).
bool launched_by_mpi();
int launcher_processes();

// The team of one: rank 0 of 1.
class OneProcess final : public ProcessTeam {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  bool broadcast(bool value) override { return value; }
  std::vector<std::string> gather(const std::string& bytes) override { return {bytes}; }
};

}  // namespace mg
