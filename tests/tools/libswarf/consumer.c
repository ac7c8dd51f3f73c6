/* SPDX-License-Identifier: MPL-2.0 */
/* consumer.c -- a program of someone else's, built against an installed
 * libswarf (with pkg-config or with CMake's find_package) to prove that the
 * installation is usable: headers under <swarf/>, the library, its link
 * interface.
 *
 * It mills a slot with a flat end mill through the streaming handle (the
 * program fed in pieces that split lines) and checks the removed volume
 * against the analytic one: a D = 4 mm cutter plunged 1 mm deep and moved
 * 10 mm removes a stadium prism, depth * (L D + pi D^2 / 4) = 52.566 mm^3.
 * Also: the header's and the library's versions agree, the line callback
 * sees every line that moved, progress is called. It runs in a thread with
 * a 256 KB stack, as a plug-in's worker might: the config comes from
 * swarf_sim_config_new (over half a megabyte), and nothing in the library
 * may need more stack than that.
 */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include <swarf/swarf.h>

static int failures;
#define EXPECT(cond, ...)                                                                          \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      failures++;                                                                                  \
      fprintf(stderr, "consumer: %s: ", #cond);                                                    \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fputc('\n', stderr);                                                                         \
    }                                                                                              \
  } while (0)

typedef struct {
  long progress_calls, lines;
  double line_path;
} tally;

static int on_progress(void *user, const swarf_sim_progress *p) {
  ((tally *)user)->progress_calls++;
  (void)p;
  return 0;
}

static void on_line(void *user, const swarf_line_result *r) {
  tally *t = user;
  t->lines++;
  t->line_path += r->path_mm;
}

static int mill(void) {
  static const char program[] = "G21 G90 G17\nG0 X5 Y5 Z2\nG1 Z-1 F100\nG1 X15\nG0 Z2\nM2\n";
  const double depth = 1.0, d = 4.0, len = 10.0;
  const double analytic = depth * (len * d + 3.14159265358979323846 * d * d / 4.0);

  EXPECT(strcmp(swarf_version(), SWARF_VERSION_STRING) == 0, "library %s, headers %s",
         swarf_version(), SWARF_VERSION_STRING);

  swarf_sim_config *cfg = swarf_sim_config_new();
  swarf_error err;
  swarf_sim_tool tool;
  tally t = {0, 0, 0.0};
  if (cfg == NULL) return fputs("consumer: out of memory\n", stderr), 1;
  if (swarf_sim_parse_stock("box:0,0,-5,20,10,0", &cfg->stock, &err) != SWARF_OK ||
      swarf_sim_parse_tool("T1=flat,D4,L12", &tool, &err) != SWARF_OK ||
      swarf_sim_config_add_tool(cfg, &tool, &err) != SWARF_OK) {
    fprintf(stderr, "consumer: %s\n", err.message);
    swarf_sim_config_free(cfg);
    return 1;
  }
  cfg->voxel = 0.1;
  cfg->cb.progress = on_progress;
  cfg->cb.line = on_line;
  cfg->cb.user = &t;

  swarf_sim *sim = NULL;
  const swarf_status made = swarf_sim_new(cfg, "slot.ngc", &sim, &err);
  swarf_sim_config_free(cfg); /* the handle copied what it needs */
  if (made != SWARF_OK) {
    fprintf(stderr, "consumer: swarf_sim_new: %s\n", err.message);
    return 1;
  }
  const size_t n = sizeof program - 1, cut1 = 17, cut2 = 30; /* mid-line splits */
  swarf_status st = swarf_sim_feed(sim, program, cut1);
  if (st == SWARF_OK) st = swarf_sim_feed(sim, program + cut1, cut2 - cut1);
  if (st == SWARF_OK) st = swarf_sim_feed(sim, program + cut2, n - cut2);
  if (st == SWARF_OK) st = swarf_sim_finish(sim);
  if (st != SWARF_OK) {
    char buf[1024];
    swarf_error_format(swarf_sim_error(sim), buf, sizeof buf);
    fprintf(stderr, "consumer: %s: %s\n", swarf_status_name(st), buf);
    swarf_sim_free(sim);
    return 1;
  }
  const swarf_sim_report *rep = swarf_sim_get_report(sim);
  const double removed = rep->volume_before - rep->volume_after;
  swarf_stock *stock = swarf_sim_take_stock(sim);
  const double box = 20.0 * 10.0 * 5.0;
  EXPECT(fabs(rep->volume_before - box) < 1e-3 * box, "volume before %.6f, box %.6f",
         rep->volume_before, box);
  EXPECT(fabs(removed - analytic) < 0.01 * analytic, "removed %.4f mm^3, analytic %.4f", removed,
         analytic);
  EXPECT(stock != NULL && fabs(swarf_stock_volume(stock) - rep->volume_after) < 1e-9 * box,
         "taken stock's volume");
  EXPECT(rep->moves == 4, "%ld moves", rep->moves);
  EXPECT(t.progress_calls >= rep->moves, "%ld progress calls", t.progress_calls);
  EXPECT(t.lines == 4, "%ld lines reported", t.lines);
  EXPECT(fabs(t.line_path - rep->path_mm) < 1e-9 * rep->path_mm, "line paths sum %.9f, path %.9f",
         t.line_path, rep->path_mm);
  swarf_stock_free(stock);
  swarf_sim_free(sim);
  printf("consumer (libswarf %s): removed %.4f mm^3, analytic %.4f: %s\n", swarf_version(), removed,
         analytic, failures ? "FAILED" : "ok");
  return failures ? 1 : 0;
}

static void *mill_thread(void *rc) {
  *(int *)rc = mill();
  return NULL;
}

int main(void) {
  pthread_attr_t attr;
  pthread_t th;
  int rc = 1;
  if (pthread_attr_init(&attr) != 0 || pthread_attr_setstacksize(&attr, 256 * 1024) != 0 ||
      pthread_create(&th, &attr, mill_thread, &rc) != 0)
    return fputs("consumer: cannot start a thread with a 256 KB stack\n", stderr), 1;
  pthread_join(th, NULL);
  pthread_attr_destroy(&attr);
  return rc;
}
