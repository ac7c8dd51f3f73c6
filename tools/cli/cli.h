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
