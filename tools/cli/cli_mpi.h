/* SPDX-License-Identifier: MPL-2.0 */
/* cli_mpi.h -- `swarf simulate` on several processes (mpirun, srun): OpenMPI
 * behind the driver's swarf_sim_comm (swarf_sim.h).
 *
 * Role: start MPI when the program runs under a launcher (mpirun's
 * OMPI_COMM_WORLD_SIZE, srun's PMIX_RANK or PMI_RANK), give the driver its
 * two collectives, agree on the outcome of the checks made before the run,
 * end all ranks when one fails inside the run. Rank 0 speaks and writes:
 * the other ranks' stdout and stderr go to /dev/null, except for the
 * message of an internal failure of their own. Built without OpenMPI
 * (SWARF_MPI off) or run without a launcher: one process, no MPI call.
 */
#ifndef SWARF_CLI_MPI_H
#define SWARF_CLI_MPI_H

#include "swarf_sim.h"

typedef struct {
  swarf_sim_comm comm; /* comm.size 1: one process */
  int active;          /* MPI was started (MPI_Init) */
  int saved_stderr;    /* ranks > 0: their own stderr (-1: none) */
} swarf_cli_mpi;

/* Start MPI under a launcher (else one process). 0, or 1 after a message. */
int swarf_cli_mpi_start(swarf_cli_mpi *m);

/* The checks before the run: every rank passes its exit status (0: fine);
 * all get the largest. When rank 0's was 0 but another's was not, rank 0
 * says which rank could not start. */
int swarf_cli_mpi_agree(swarf_cli_mpi *m, int rc);

/* A failure of this rank only, inside the run (the others may be waiting
 * for it): its message on its own stderr, then every rank ends with
 * `status` (MPI_Abort). Returns only without MPI. */
void swarf_cli_mpi_abort(swarf_cli_mpi *m, const char *msg, int status);

/* Every rank must run the same job: hashes (FNV-1a, 64 bits) of the
 * arguments and of each input file's bytes (names[i] = files[i], NULL ones
 * skipped), compared with rank 0's before any work; a rank given other
 * inputs would wait for ever in a collective the others never reach. 0 when
 * all agree, else 2 on every rank, rank 0 naming the rank and what differs. */
int swarf_cli_mpi_same_inputs(swarf_cli_mpi *m, int argc, char **argv, const char *const *names,
                              const char *const *files, int nfiles);

/* The end: MPI_Finalize when started. Returns rc. */
int swarf_cli_mpi_end(swarf_cli_mpi *m, int rc);

#endif
