/* SPDX-License-Identifier: MPL-2.0 */
/* cli_mpi.c -- OpenMPI behind swarf_sim_comm (cli_mpi.h). Compiled with
 * SWARF_MPI (CMake's FindMPI found OpenMPI); without it, one process.
 */
#include "cli_mpi.h"

#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* How many tasks the launcher says it started, and which variable says so:
 * srun's SLURM_STEP_NUM_TASKS (set in a step's tasks, not in an sbatch
 * script or an salloc shell, where a plain run is one process), mpirun's
 * OMPI_COMM_WORLD_SIZE, a PMI launcher's PMI_SIZE. 1 when none does. */
static long launcher_tasks(const char **var) {
  static const char *const vars[] = {"SLURM_STEP_NUM_TASKS", "OMPI_COMM_WORLD_SIZE", "PMI_SIZE"};
  for (size_t i = 0; i < sizeof vars / sizeof vars[0]; i++) {
    const char *v = getenv(vars[i]);
    long n = v != NULL ? strtol(v, NULL, 10) : 0;
    if (n > 1) {
      *var = vars[i];
      return n;
    }
  }
  return 1;
}

/* Several tasks launched, but this one sees a world of one: each would run
 * the whole job and write the same outputs. Refused before any work. */
static int refuse_copies(const swarf_cli_mpi *m) {
  const char *var = NULL;
  long n = launcher_tasks(&var);
  if (m->comm.size > 1 || n <= 1) return 0;
  if (strcmp(var, "SLURM_STEP_NUM_TASKS") == 0)
    fprintf(stderr,
            "swarf simulate: this is one of %ld tasks of a Slurm step, but MPI sees one "
            "process: each task would run the whole job and write the same outputs. Start it "
            "with `srun --mpi=pmix` (or SLURM_MPI_TYPE=pmix, or MpiDefault=pmix in "
            "slurm.conf); nothing was written\n",
            n);
  else
    fprintf(stderr,
            "swarf simulate: the launcher started %ld tasks (%s) but MPI sees one process: "
            "each would run the whole job. Use the launcher of the MPI swarf was built with "
            "(OpenMPI's mpirun); nothing was written\n",
            n, var);
  return 2;
}

#ifdef SWARF_MPI
#include <mpi.h>

/* Messages of at most 1 GiB (MPI counts are ints). */
#define CHUNK ((size_t)1 << 30)

static int mpi_allgather(void *user, const void *send, size_t n, void *recv) {
  (void)user;
  if (n > (size_t)0x7fffffff) return 1;
  return MPI_Allgather(send, (int)n, MPI_BYTE, recv, (int)n, MPI_BYTE, MPI_COMM_WORLD) !=
         MPI_SUCCESS;
}

static int send_all(const void *buf, size_t n) {
  for (size_t at = 0; at < n; at += CHUNK) {
    size_t k = n - at < CHUNK ? n - at : CHUNK;
    if (MPI_Send((const char *)buf + at, (int)k, MPI_BYTE, 0, 7, MPI_COMM_WORLD) != MPI_SUCCESS)
      return 1;
  }
  return 0;
}

static int recv_all(void *buf, size_t n, int from) {
  for (size_t at = 0; at < n; at += CHUNK) {
    size_t k = n - at < CHUNK ? n - at : CHUNK;
    if (MPI_Recv((char *)buf + at, (int)k, MPI_BYTE, from, 7, MPI_COMM_WORLD, MPI_STATUS_IGNORE) !=
        MPI_SUCCESS)
      return 1;
  }
  return 0;
}

/* Sizes first (a gather), then each rank's bytes in turn: rank 0 holds one
 * other rank's slab at a time. */
static int mpi_gather(void *user, const void *send, size_t n,
                      int (*take)(void *ctx, int rank, const void *buf, size_t n), void *ctx) {
  swarf_cli_mpi *m = user;
  unsigned long long mine = n, *sizes = NULL;
  int rc = 0;
  if (m->comm.rank == 0 && (sizes = calloc((size_t)m->comm.size, sizeof *sizes)) == NULL)
    MPI_Abort(MPI_COMM_WORLD, 1);
  MPI_Gather(&mine, 1, MPI_UNSIGNED_LONG_LONG, sizes, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  if (m->comm.rank != 0) return n > 0 ? send_all(send, n) : 0;
  for (int r = 1; r < m->comm.size; r++) {
    void *buf = malloc(sizes[r] > 0 ? (size_t)sizes[r] : 1);
    if (buf == NULL) MPI_Abort(MPI_COMM_WORLD, 1);
    if (sizes[r] > 0 && recv_all(buf, (size_t)sizes[r], r) != 0) rc = 1;
    if (rc == 0 && take(ctx, r, buf, (size_t)sizes[r]) != 0) rc = 1;
    free(buf);
  }
  free(sizes);
  return rc;
}

static int launched(void) {
  return getenv("OMPI_COMM_WORLD_SIZE") != NULL || getenv("PMIX_RANK") != NULL ||
         getenv("PMI_RANK") != NULL;
}

int swarf_cli_mpi_start(swarf_cli_mpi *m) {
  memset(m, 0, sizeof *m);
  m->comm.size = 1;
  m->saved_stderr = -1;
  if (!launched()) return refuse_copies(m);
  if (MPI_Init(NULL, NULL) != MPI_SUCCESS) {
    fprintf(stderr, "swarf simulate: MPI could not start\n");
    return 1;
  }
  m->active = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &m->comm.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &m->comm.size);
  m->comm.allgather = mpi_allgather;
  m->comm.gather = mpi_gather;
  m->comm.user = m;
  if (refuse_copies(m)) {
    MPI_Finalize();
    m->active = 0;
    return 2;
  }
  if (m->comm.rank != 0) { /* rank 0 speaks */
    fflush(NULL);
    m->saved_stderr = dup(2);
    int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, 1);
      dup2(null, 2);
      close(null);
    }
  }
  return 0;
}

int swarf_cli_mpi_agree(swarf_cli_mpi *m, int rc) {
  int *all, worst = rc, who = -1;
  if (!m->active || m->comm.size == 1) return rc;
  if ((all = malloc(sizeof *all * (size_t)m->comm.size)) == NULL) MPI_Abort(MPI_COMM_WORLD, 1);
  MPI_Allgather(&rc, 1, MPI_INT, all, 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < m->comm.size; r++)
    if (all[r] > worst) worst = all[r], who = r;
  if (m->comm.rank == 0 && rc == 0 && worst != 0)
    fprintf(stderr,
            "swarf simulate: rank %d of %d could not start (exit status %d): does it "
            "see the same program and inputs?\n",
            who, m->comm.size, worst);
  free(all);
  return worst;
}

void swarf_cli_mpi_abort(swarf_cli_mpi *m, const char *msg, int status) {
  if (!m->active || m->comm.size == 1) return;
  if (m->saved_stderr >= 0) {
    char line[1200];
    int n = snprintf(line, sizeof line, "swarf simulate: rank %d: %s\n", m->comm.rank, msg);
    if (n > 0 && write(m->saved_stderr, line, (size_t)n) < 0) n = 0;
  } else {
    fprintf(stderr, "%s\n", msg);
  }
  fflush(NULL);
  MPI_Abort(MPI_COMM_WORLD, status);
}

#define MAX_HASHED 8

static uint64_t fnv(uint64_t h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++)
    h = (h ^ p[i]) * 1099511628211ULL;
  return h;
}

/* The file's bytes hashed; a file that cannot be read hashes as its name
 * (its reader reports the error later, on every rank alike). */
static uint64_t hash_file(const char *path) {
  unsigned char buf[1 << 16];
  uint64_t h = 14695981039346656037ULL;
  size_t n;
  FILE *f = fopen(path, "rb");
  if (f == NULL) return fnv(h, path, strlen(path));
  while ((n = fread(buf, 1, sizeof buf, f)) > 0)
    h = fnv(h, buf, n);
  fclose(f);
  return h;
}

int swarf_cli_mpi_same_inputs(swarf_cli_mpi *m, int argc, char **argv, const char *const *names,
                              const char *const *files, int nfiles) {
  uint64_t mine[MAX_HASHED] = {14695981039346656037ULL}, *all;
  int bad_rank = -1, bad_item = 0;
  if (!m->active || m->comm.size == 1) return 0;
  if (nfiles > MAX_HASHED - 1) nfiles = MAX_HASHED - 1;
  for (int i = 1; i < argc; i++)
    mine[0] = fnv(mine[0], argv[i], strlen(argv[i]) + 1);
  for (int i = 0; i < nfiles; i++)
    mine[i + 1] = files[i] != NULL ? hash_file(files[i]) : 0;
  if ((all = malloc(sizeof mine * (size_t)m->comm.size)) == NULL) MPI_Abort(MPI_COMM_WORLD, 1);
  MPI_Allgather(mine, MAX_HASHED, MPI_UINT64_T, all, MAX_HASHED, MPI_UINT64_T, MPI_COMM_WORLD);
  for (int r = 1; r < m->comm.size && bad_rank < 0; r++)
    for (int i = 0; i <= nfiles && bad_rank < 0; i++)
      if (all[r * MAX_HASHED + i] != all[i]) bad_rank = r, bad_item = i;
  free(all);
  if (bad_rank < 0) return 0;
  if (m->comm.rank == 0)
    fprintf(stderr,
            "swarf simulate: rank %d of %d was given a different %s than rank 0: every rank must "
            "run the same command on the same files; nothing was written\n",
            bad_rank, m->comm.size, bad_item == 0 ? "command line" : names[bad_item - 1]);
  return 2;
}

int swarf_cli_mpi_end(swarf_cli_mpi *m, int rc) {
  if (m->active) MPI_Finalize();
  m->active = 0;
  return rc;
}

#else /* one process */

int swarf_cli_mpi_start(swarf_cli_mpi *m) {
  memset(m, 0, sizeof *m);
  m->comm.size = 1;
  m->saved_stderr = -1;
  if (getenv("OMPI_COMM_WORLD_SIZE") != NULL && atoi(getenv("OMPI_COMM_WORLD_SIZE")) > 1) {
    fprintf(stderr, "swarf simulate: this swarf was built without MPI (SWARF_MPI off): run it "
                    "without mpirun, or rebuild with libopenmpi-dev\n");
    return 2;
  }
  return refuse_copies(m);
}

int swarf_cli_mpi_agree(swarf_cli_mpi *m, int rc) {
  (void)m;
  return rc;
}

void swarf_cli_mpi_abort(swarf_cli_mpi *m, const char *msg, int status) {
  (void)m, (void)msg, (void)status;
}

int swarf_cli_mpi_same_inputs(swarf_cli_mpi *m, int argc, char **argv, const char *const *names,
                              const char *const *files, int nfiles) {
  (void)m, (void)argc, (void)argv, (void)names, (void)files, (void)nfiles;
  return 0;
}

int swarf_cli_mpi_end(swarf_cli_mpi *m, int rc) {
  (void)m;
  return rc;
}

#endif
