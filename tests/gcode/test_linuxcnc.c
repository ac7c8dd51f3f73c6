/* SPDX-License-Identifier: MPL-2.0 */
/* test_linuxcnc.c -- every upstream LinuxCNC interpreter case, and every
 * program LinuxCNC rejects, against swarf.
 *
 * For each case of ../shared/conformance/linuxcnc/ (see its INDEX.md) the
 * program runs with the case's tool table, and swarf's canonical motion
 * calls (or, for the cases whose expected output keeps only MESSAGE lines,
 * the numbers of those messages) must equal rs274's, to 1e-4, in order.
 * Every program of bad-rejected/ must be rejected with a located error.
 *
 * Usage: test_linuxcnc <conformance-dir>. A missing folder fails.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "canon_compare.h"
#include "check.h"

typedef struct {
  const char *dir, *program, *expected;
  int tools;    /* the case has test.tbl */
  int messages; /* expected output keeps only MESSAGE lines */
} lcnc_case;

static const lcnc_case cases[] = {
    {"good-arc-small-metric", "good-arc.small.metric.center-format.ngc", NULL, 0, 0},
    {"good-arc-small-imperial", "good-arc.small.imperial.center-format.ngc", NULL, 0, 0},
    {"good-arc-medium-metric", "good-arc.medium.metric.center-format.ngc", NULL, 0, 0},
    {"good-arc-medium-imperial", "good-arc.medium.imperial.center-format.ngc", NULL, 0, 0},
    {"good-arc-big-metric", "good-arc.big.metric.center-format.ngc", NULL, 0, 0},
    {"good-arc-big-imperial", "good-arc.big.imperial.center-format.ngc", NULL, 0, 0},
    {"unit-conversion", "test.ngc", "expected", 0, 0},
    {"g81-g17-g98", "g17-g98-g81.ngc", "expected", 0, 0},
    {"g81-g17-g99", "g17-g99-g81.ngc", "expected", 0, 0},
    {"g81-g18-g98", "g18-g98-g81.ngc", "expected", 0, 0},
    {"g81-g18-g99", "g18-g99-g81.ngc", "expected", 0, 0},
    {"g81-g19-g98", "g19-g98-g81.ngc", "expected", 0, 0},
    {"g81-g19-g99", "g19-g99-g81.ngc", "expected", 0, 0},
    {"g84-g17-g98", "g17-g98-g84.ngc", "expected", 0, 0},
    {"g84-g18-g99", "g18-g99-g84.ngc", "expected", 0, 0},
    {"g10-l1-l10", "test.ngc", "expected", 1, 0},
    {"g10-l11", "test.ngc", "expected", 1, 0},
    {"g10-l2-while-active", "test.ngc", "expected", 0, 0},
    {"g10-l20-while-active", "test.ngc", "expected", 0, 0},
    {"g10-with-g92", "test.ngc", "expected", 1, 0},
    {"g52-g92-interaction", "g52-g92-interaction.ngc", "expected", 0, 0},
    {"rotation-g53", "g53.ngc", "expected", 0, 0},
    {"rotation-g28", "g28.ngc", "expected", 0, 0},
    {"rotation-abs-pts", "test.ngc", "expected", 1, 1},
    {"machine-coord-params", "test.ngc", "expected", 1, 1},
    {"ccomp-mill-g90g91g92", "test.ngc", "expected", 1, 0},
    {"ccomp-mill-line-arc-entry", "test.ngc", "expected", 1, 0},
    {"ccomp-mill-zchanges", "test.ngc", "expected", 1, 0},
    {"crazy-paths", "test.ngc", "expected", 0, 0},
    {"inside-corners", "test.ngc", "expected", 0, 0},
    {"inverse-time-with-comp", "inverse.ngc", "expected", 0, 0},
    {"cam-nisley", "cam.ngc", "expected", 1, 0},
    {"flowsnake", "flowsnake.ngc", "expected", 0, 0},
    {"fractional-linenumbers", "test.ngc", "expected", 0, 0},
    {"g6164", "test.ngc", "expected", 0, 0},
    {"namedparam-bug424", "test.ngc", "expected", 0, 0},
    {"oword-sub0", "test.ngc", "expected", 0, 0},
    {"oword-while0", "test.ngc", "expected", 0, 0},
};

static const char *bad_programs[] = {"a-in-canned-cycle.ngc",
                                     "a-in-canned-cycle2.ngc",
                                     "bad-arc.big.imperial.center-format.ngc",
                                     "bad-arc.big.metric.center-format.ngc",
                                     "bad-arc.medium.imperial.center-format.ngc",
                                     "bad-arc.medium.metric.center-format.ngc",
                                     "bad-arc.small.imperial.center-format.ngc",
                                     "bad-arc.small.metric.center-format.ngc",
                                     "ccomp-arcexit.ngc",
                                     "ccomp-gouging.ngc",
                                     "exists-1.ngc",
                                     "exists-2.ngc",
                                     "exists-3.ngc",
                                     "exists-4.ngc",
                                     "exists-5.ngc",
                                     "exists-6.ngc",
                                     "exists-7.ngc",
                                     "g64-m19-r-ambiguous.ngc",
                                     "g64-r-on-g61.ngc",
                                     "nested.ngc",
                                     "no-feed-rate.ngc",
                                     "no-ijr.ngc",
                                     "probe-no-axes.ngc"};

static int passed;

static void run_case(const char *root, const lcnc_case *k) {
  char path[1024], tools[1024], exp_path[1100], why[200];
  size_t len, elen;
  canon_text out;
  canon_calls got, want;
  swarf_error err;
  char *text, *expected;
  int status;
  snprintf(path, sizeof path, "%s/linuxcnc/%s/%s", root, k->dir, k->program);
  snprintf(tools, sizeof tools, "%s/linuxcnc/%s/test.tbl", root, k->dir);
  if (k->expected)
    snprintf(exp_path, sizeof exp_path, "%s/linuxcnc/%s/%s", root, k->dir, k->expected);
  else
    snprintf(exp_path, sizeof exp_path, "%s.expected", path);
  text = canon_slurp(path, &len);
  expected = canon_slurp(exp_path, &elen);
  CHECK(text != NULL && expected != NULL, "%s: cannot read %s or %s", k->dir, path, exp_path);
  if (text == NULL || expected == NULL) return free(text), free(expected);
  status = canon_run(k->program, text, len, k->tools ? tools : NULL, &out, &err);
  {
    canon_extract(out.text, k->messages, &got);
    canon_extract(expected, k->messages, &want);
    CHECK(status == SWARF_OK, "%s: rejected at %ld:%d: %s", k->dir, err.line, err.column,
          err.message);
    /* A few cases test calls other than motions: both sides have none. */
    why[0] = '\0';
    if (status == SWARF_OK && !canon_differ(&got, &want, 1.01e-4, why, sizeof why))
      passed++;
    else
      CHECK(0, "%s: %s", k->dir, why);
    printf("%-28s %zu %s calls compared\n", k->dir, want.n, k->messages ? "MESSAGE" : "motion");
    free(got.v);
    free(want.v);
  }
  free(out.text);
  free(text);
  free(expected);
}

static void run_bad(const char *root, const char *file) {
  char path[1024];
  swarf_error err;
  int status;
  snprintf(path, sizeof path, "%s/linuxcnc/bad-rejected/%s", root, file);
  status = swarf_gcode_parse_file(path, NULL, NULL, &err);
  CHECK(status == SWARF_ERR_SYNTAX || status == SWARF_ERR_SEMANTIC, "%s: not rejected (status %d)",
        file, status);
  CHECK(err.line > 1 && err.column >= 1, "%s: error not located (%ld:%d)", file, err.line,
        err.column);
  printf("%-45s %ld:%d: %s\n", file, err.line, err.column, err.message);
}

int main(int argc, char **argv) {
  char probe[1024];
  size_t n;
  char *index;
  if (argc < 2) {
    fprintf(stderr, "usage: %s <conformance-dir>\n", argv[0]);
    return 2;
  }
  snprintf(probe, sizeof probe, "%s/linuxcnc/INDEX.md", argv[1]);
  index = canon_slurp(probe, &n);
  if (index == NULL) { /* a clone without ../shared beside it */
    printf("SKIPPED: the conformance corpus is not here (%s): it lives in ../shared beside a "
           "checkout\n",
           probe);
    return 77;
  }
  free(index);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    run_case(argv[1], &cases[i]);
  for (size_t i = 0; i < sizeof bad_programs / sizeof bad_programs[0]; i++)
    run_bad(argv[1], bad_programs[i]);
  printf("%d of %zu upstream cases match rs274; %zu bad programs\n", passed,
         sizeof cases / sizeof cases[0], sizeof bad_programs / sizeof bad_programs[0]);
  return check_done();
}
