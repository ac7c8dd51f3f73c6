/* SPDX-License-Identifier: MPL-2.0 */
/* cli.h -- the subcommands of the `swarf` executable.
 *
 * Each takes argv with argv[0] = the command's name and returns the process
 * exit status (0 ok, 1 internal failure, 2 bad input). Only tools/ talks to
 * the terminal.
 */
#ifndef SWARF_CLI_H
#define SWARF_CLI_H

#ifdef __cplusplus
extern "C" {
#endif

int swarf_cli_simulate(int argc, char **argv);
int swarf_cli_parse(int argc, char **argv);
int swarf_cli_info(int argc, char **argv);
int swarf_cli_render(int argc, char **argv);
int swarf_cli_envelope(int argc, char **argv);
int swarf_cli_help(const char *command);

/* Output paths (outputs.c): refuses, naming `flag` on stderr and returning
 * 2, an empty name, a name ending in '/', an existing folder, symbolic link,
 * block device or socket, or a missing or unwritable folder; a character
 * device or FIFO is accepted (written into). NULL path: 0. */
int swarf_cli_output_ok(const char *cmd, const char *flag, const char *path);

/* "X,Y,Z": three finite numbers of at most 1e6 (mm) into out; -1 when the
 * text is anything else (verify.c; the caller says what is wrong). */
int swarf_cli_read_point(const char *val, double out[3]);

/* A file named on the command line and the flag (or role) that named it. */
typedef struct {
  const char *flag, *path; /* path NULL: not given */
} swarf_cli_path;

/* 2 (with a message) when an output is one of the inputs or another output
 * (same device and inode, or the same absolute name), else 0. */
int swarf_cli_outputs_distinct(const char *cmd, const swarf_cli_path *outs, int nout,
                               const swarf_cli_path *ins, int nin);

/* 2 with a message when an output named *EXT lies in one of `dirs` (a
 * ':'-separated list, may be NULL), given by `flag`: a subroutine file the
 * program may call would be overwritten. */
int swarf_cli_outputs_outside(const char *cmd, const swarf_cli_path *outs, int nout,
                              const char *flag, const char *dirs, const char *ext);

/* A progress bar on stderr, drawn only when stderr is a terminal. */
typedef struct {
  int enabled;
  double start;     /* monotonic seconds */
  double last_draw; /* monotonic seconds */
  double fraction;
} swarf_progress;

void swarf_progress_init(swarf_progress *pb);
/* fraction in [0, 1] or < 0 to keep the last; moves done so far. */
void swarf_progress_update(void *pb, double fraction, long moves);
void swarf_progress_finish(swarf_progress *pb);
double swarf_progress_now(void);

#ifdef __cplusplus
}
#endif
#endif
