/* SPDX-License-Identifier: MPL-2.0 */
/* helix_progress.c -- a helix of 10,000 turns about a horizontal axis (G18 or
 * G19, inputs/arc_p10000_g18.ngc, _g19.ngc) through the simulation handle:
 * it finishes (ctest's TIMEOUT is the hang limit, not a benchmark), progress
 * is told within the helix's removal pass, increasing, and the removed volume
 * is the analytic one.
 *
 * Usage: helix_progress PROGRAM.ngc. The stock is ../shared/reliability's S
 * line (box 40 x 40 x 10 mm, ball D3, here L20 and a 0.25 mm voxel). The
 * helix turns 10,000 times on a circle of radius 5 about (20, -5) across the
 * axis (tips from z = -10 to 0), the axis coordinate from -5 to 45: 0.005 mm
 * a turn, so at every point of the stock's 40 mm along the axis every phase
 * passes within 0.0025 mm (the ball's surface rises by < 3e-6 mm there). The
 * removed cross-section is the region above the lowest ball surface, whose
 * centres run on the circle of radius 5 about (20, -3.5): the outer edge of
 * the annulus of radius 6.5 about it, i.e. 13 x 3.5 + pi 6.5^2 / 2 mm^2
 * (the balls' columns reach above the stock's top from any tip). Volume:
 * 40 times that, within 0.5 % (OpenVDB's volume of the level sets).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "swarf_sim.h"

#define HELIX_LINE 5 /* the G2 line of both programs */

typedef struct {
  int in_pass, increasing;
  double last;
} heard;

static int on_progress(void *user, const swarf_sim_progress *p) {
  heard *h = user;
  if (p->pass < 0.0 || p->line != HELIX_LINE) return 0;
  if (!(p->pass >= 0.0 && p->pass <= 1.0 && p->pass > h->last)) h->increasing = 0;
  h->last = p->pass;
  h->in_pass++;
  return 0;
}

static char *read_text(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  char *buf = f != NULL ? malloc(4096) : NULL;
  *len = buf != NULL ? fread(buf, 1, 4095, f) : 0;
  if (f != NULL) fclose(f);
  return buf;
}

int main(int argc, char **argv) {
  swarf_sim_config cfg;
  swarf_sim_tool t;
  swarf_sim_report rep;
  swarf_stock *out = NULL;
  swarf_error err;
  heard h = {0, 1, -1.0};
  size_t len;
  char *text = argc == 2 ? read_text(argv[1], &len) : NULL;
  const double want = 40.0 * (13.0 * 3.5 + M_PI * 6.5 * 6.5 / 2.0);
  if (text == NULL) {
    fprintf(stderr, "usage: helix_progress PROGRAM.ngc (a readable file)\n");
    return 2;
  }
  swarf_sim_config_init(&cfg);
  cfg.voxel = 0.25;
  cfg.threads = 1;
  cfg.tick = -1.0; /* after every chunk of blocks */
  cfg.batch = 1;
  cfg.cb = (swarf_sim_callbacks){.progress = on_progress, .user = &h};
  CHECK(swarf_sim_parse_stock("box:0,0,-10,40,40,0", &cfg.stock, &err) == SWARF_OK, "%s",
        err.message);
  CHECK(swarf_sim_parse_tool("T1=ball,D3,L20", &t, &err) == SWARF_OK, "%s", err.message);
  CHECK(swarf_sim_config_add_tool(&cfg, &t, &err) == SWARF_OK, "%s", err.message);
  CHECK(swarf_sim_run_text(&cfg, argv[1], text, len, &out, &rep, &err) == SWARF_OK, "%s",
        err.message);
  if (out != NULL) {
    double removed = rep.volume_before - rep.volume_after;
    printf("%s: %d progress calls within the helix's pass; removed %.2f mm^3 vs %.2f analytic "
           "(%+.3f%%)\n",
           argv[1], h.in_pass, removed, want, 100.0 * (removed - want) / want);
    CHECK(h.in_pass >= 3 && h.increasing, "progress within the helix's pass (line %d), increasing",
          HELIX_LINE);
    CHECK(fabs(removed - want) <= 0.005 * want, "removed %.3f vs %.3f", removed, want);
    CHECK(swarf_stock_check(out, &err) == SWARF_OK, "level set valid: %s", err.message);
    swarf_stock_free(out);
  }
  free(text);
  return check_done();
}
