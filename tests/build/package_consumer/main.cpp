// Reaches into every layer a user of the package links: a physics function (propagation), the
// compiled-in paper scenario (experiment, through toml++), the raw-data writer's library (libhdf5)
// and the sweep module (MPI where fogradar was built with it).
#include <cstdio>

#include "fogradar/experiment/raw_file.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/propagation/visibility.hpp"
#include "fogradar/sweep/mpi.hpp"

int main() {
  const fogradar::experiment::Scenario paper = fogradar::experiment::paper_scenario();
  paper.validate();
  std::printf("visibility_m %.6f\n", fogradar::propagation::visibility_m_from_extinction(0.9));
  std::printf("layers %zu\n", paper.chamber.layers_in_use());
  // Taking the writer's address links it, and libhdf5 with it.
  void (fogradar::experiment::RawFile::*finish)() = &fogradar::experiment::RawFile::finish;
  std::printf("raw_file %d\n", finish != nullptr ? 1 : 0);
  std::printf("mpi %d\n", fogradar::sweep::built_with_mpi() ? 1 : 0);
  return 0;
}
