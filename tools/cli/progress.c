/* SPDX-License-Identifier: MPL-2.0 */
/* progress.c -- a one-line progress bar on stderr for long runs.
 *
 * Drawn only when stderr is a terminal (never into pipes or logs), at most
 * ten times a second; the caller owns the swarf_progress value.
 */
#include <stdio.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

double swarf_progress_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

void swarf_progress_init(swarf_progress *pb) {
  pb->enabled = isatty(fileno(stderr));
  pb->start = swarf_progress_now();
  pb->last_draw = 0.0;
  pb->fraction = 0.0;
}

void swarf_progress_update(void *ctx, double fraction, long moves) {
  swarf_progress *pb = ctx;
  double t = swarf_progress_now();
  char bar[41];
  int filled;
  if (!pb->enabled) return;
  if (fraction >= 0.0) pb->fraction = fraction > 1.0 ? 1.0 : fraction;
  if (t - pb->last_draw < 0.1) return;
  pb->last_draw = t;
  filled = (int)(pb->fraction * 40.0);
  for (int i = 0; i < 40; i++)
    bar[i] = i < filled ? '#' : '.';
  bar[40] = '\0';
  fprintf(stderr, "\r[%s] %3d%%  %ld moves  %.1f s ", bar, (int)(pb->fraction * 100.0), moves,
          t - pb->start);
  fflush(stderr);
}

void swarf_progress_finish(swarf_progress *pb) {
  if (pb->enabled && pb->last_draw > 0.0) fputs("\r\033[K", stderr);
}
