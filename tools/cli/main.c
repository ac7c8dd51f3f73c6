/* SPDX-License-Identifier: MPL-2.0 */
/* main.c -- the `swarf` command: subcommands, options, progress, summary.
 *
 * Exit status: 0 success, 1 internal failure (I/O, memory), 2 bad input
 * (options, G-code, files), with a message on stderr that says what to do.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "cli_stock.h"

static const char usage[] =
    "usage: swarf <command> [options]\n"
    "\n"
    "Simulates CNC milling: plays a G-code program through the machine, removes the\n"
    "exact swept volume of the cutter from a voxel stock, and writes what remains.\n"
    "\n"
    "commands:\n"
    "  simulate PROGRAM --stock box:... --tool T1=... --out FILE.vdb [--mesh FILE]\n"
    "           [--image FILE.png] [--html FILE.html] [--design FILE.stl]\n"
    "           [--report FILE.json] [...]\n"
    "                     mill PROGRAM into a stock; write .vdb, mesh, picture,\n"
    "                     page, report; verify against the design\n"
    "  parse PROGRAM      list the canonical moves of a program (checks it)\n"
    "  info FILE.vdb      describe a stock grid: voxel, volume, bounds, validity\n"
    "  render FILE.vdb --image FILE.png [--view V] [--design FILE]   picture of a grid\n"
    "  compare A.vdb B.vdb|B.stl   deviation of a result from another or a design\n"
    "  envelope --qss A,B,C,D,E,F --axis W --tdot V --half-angle B [--exact]\n"
    "                     characteristic curve of a moving QSS (exact with --exact)\n"
    "  help [COMMAND]     this text, or a command's options\n"
    "\n"
    "`swarf COMMAND --help` explains each command. Units: mm, degrees, seconds.\n"
    "Environment: simulate, info, render and compare run malloc on transparent huge\n"
    "pages (swarf restarts itself once with GLIBC_TUNABLES=glibc.malloc.hugetlb=1)\n"
    "unless GLIBC_TUNABLES is set or SWARF_HUGEPAGES=0.\n";

/* Transparent huge pages for malloc's heaps. A run touches its grid's leaves
 * once each, and on the virtual machines we measure on every fresh page costs
 * a paravirtualized fault: with glibc's tunable (read only at start-up, hence
 * the one re-execution, which keeps the process and its arguments) bear at
 * 0.2 mm takes 9 % less wall time, the tiger at 0.5 mm 3 %, for 2-3 MB more
 * peak memory. Only the commands that make or read grids restart: the
 * re-execution costs ~18 ms, which is all of `swarf --help` and nothing
 * returns it to `parse` or `envelope`. A caller's own GLIBC_TUNABLES (this
 * re-execution's included) is left alone; if the re-execution fails, the run
 * goes on as it is. */
static void huge_pages(const char *cmd, char **argv) {
  static const char *const grids[] = {"simulate", "info", "render", "compare"};
  const char *off = getenv("SWARF_HUGEPAGES");
  int takes = 0;
  for (size_t i = 0; cmd != NULL && i < sizeof grids / sizeof grids[0]; i++)
    takes |= !strcmp(cmd, grids[i]);
  if (!takes || getenv("GLIBC_TUNABLES") != NULL || (off != NULL && !strcmp(off, "0"))) return;
  if (setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("GLIBC_TUNABLES");
}

int main(int argc, char **argv) {
  const char *cmd = argc > 1 ? argv[1] : NULL;
  huge_pages(cmd, argv);
  if (cmd == NULL || !strcmp(cmd, "--help") || !strcmp(cmd, "-h")) {
    fputs(usage, cmd ? stdout : stderr);
    return cmd ? 0 : 2;
  }
  if (!strcmp(cmd, "help")) {
    if (argc > 2) return swarf_cli_help(argv[2]);
    fputs(usage, stdout);
    return 0;
  }
  if (!strcmp(cmd, "simulate")) return swarf_cli_simulate(argc - 1, argv + 1);
  if (!strcmp(cmd, "parse")) return swarf_cli_parse(argc - 1, argv + 1);
  if (!strcmp(cmd, "info")) return swarf_cli_info(argc - 1, argv + 1);
  if (!strcmp(cmd, "render")) return swarf_cli_render(argc - 1, argv + 1);
  if (!strcmp(cmd, "compare")) return swarf_cli_compare(argc - 1, argv + 1);
  if (!strcmp(cmd, "envelope")) return swarf_cli_envelope(argc - 1, argv + 1);
  fprintf(stderr, "swarf: unknown command \"%s\"; run `swarf --help` for the list\n", cmd);
  return 2;
}
