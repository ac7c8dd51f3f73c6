/* SPDX-License-Identifier: MPL-2.0 */
/* abi.c -- writes swarf/_abi.py, the Python module's view of libswarf's ABI.
 *
 * Role: the Python module (ctypes) must agree with the C headers on every
 * struct layout and every function signature it uses. This program is
 * compiled against those headers and prints, for each struct, its size and
 * the offset and size of each field the module uses (fields it does not use
 * become padding, so fields added to a struct later keep their defaults from
 * the library's *_init), and for each function its ctypes signature. The
 * signature table is checked by the compiler: each FN line assigns the
 * function to a pointer of the type written beside its ctypes text, so a
 * header change that the table does not follow fails the build (-Werror).
 *
 * Usage: swarf_pyabi OUT.py LIBRARY -- LIBRARY is the path the module loads
 * (relative to the package folder unless absolute).
 */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "gcode.h"
#include "swarf_sim.h"
#include "swarf_version.h"

static FILE *out;

static void begin(const char *name, size_t size) {
  fprintf(out, "    (\"%s\", %zu, [\n", name, size);
}
static void field(const char *name, size_t off, size_t size, const char *type) {
  fprintf(out, "        (\"%s\", %zu, %zu, \"%s\"),\n", name, off, size, type);
}
static void end(void) {
  fprintf(out, "    ]),\n");
}

#define STRUCT(T) begin(#T, sizeof(T))
#define FIELD(T, f, type) field(#f, offsetof(T, f), sizeof(((T *)0)->f), type)

static void structs(void) {
  fprintf(out, "STRUCTS = [\n");
  STRUCT(swarf_error);
  FIELD(swarf_error, status, "c_int");
  FIELD(swarf_error, code, "c_int");
  FIELD(swarf_error, file, "c_char * 256");
  FIELD(swarf_error, line, "c_long");
  FIELD(swarf_error, column, "c_int");
  FIELD(swarf_error, word, "c_char * 32");
  FIELD(swarf_error, message, "c_char * 512");
  end();
  STRUCT(swarf_cutter);
  FIELD(swarf_cutter, shape, "c_int");
  FIELD(swarf_cutter, diameter, "c_double");
  FIELD(swarf_cutter, corner_radius, "c_double");
  FIELD(swarf_cutter, length, "c_double");
  end();
  STRUCT(swarf_machine);
  FIELD(swarf_machine, kind, "c_int");
  FIELD(swarf_machine, tcp, "c_int");
  FIELD(swarf_machine, pivot, "c_double * 3");
  end();
  STRUCT(swarf_sim_tool);
  FIELD(swarf_sim_tool, number, "c_int");
  FIELD(swarf_sim_tool, cutter, "swarf_cutter");
  FIELD(swarf_sim_tool, length, "c_double");
  end();
  STRUCT(swarf_sim_stock_spec);
  FIELD(swarf_sim_stock_spec, kind, "c_int");
  FIELD(swarf_sim_stock_spec, lo, "c_double * 3");
  FIELD(swarf_sim_stock_spec, hi, "c_double * 3");
  FIELD(swarf_sim_stock_spec, axis, "c_int");
  FIELD(swarf_sim_stock_spec, radius, "c_double");
  end();
  STRUCT(swarf_alarm);
  FIELD(swarf_alarm, kind, "c_int");
  FIELD(swarf_alarm, line, "c_long");
  FIELD(swarf_alarm, column, "c_int");
  FIELD(swarf_alarm, tool, "c_int");
  FIELD(swarf_alarm, depth, "c_double");
  FIELD(swarf_alarm, at, "c_double * 3");
  FIELD(swarf_alarm, index, "c_int");
  end();
  STRUCT(swarf_stock_deviation);
  FIELD(swarf_stock_deviation, tolerance, "c_double");
  FIELD(swarf_stock_deviation, reach, "c_double");
  FIELD(swarf_stock_deviation, stock_volume, "c_double");
  FIELD(swarf_stock_deviation, design_volume, "c_double");
  FIELD(swarf_stock_deviation, gouge_volume, "c_double");
  FIELD(swarf_stock_deviation, gouge_depth, "c_double");
  FIELD(swarf_stock_deviation, gouge_at, "c_double * 3");
  FIELD(swarf_stock_deviation, excess_volume, "c_double");
  FIELD(swarf_stock_deviation, excess_height, "c_double");
  FIELD(swarf_stock_deviation, excess_at, "c_double * 3");
  end();
  STRUCT(swarf_sim_report);
  FIELD(swarf_sim_report, lines, "c_long");
  FIELD(swarf_sim_report, moves, "c_long");
  FIELD(swarf_sim_report, cutting_moves, "c_long");
  FIELD(swarf_sim_report, rapids, "c_long");
  FIELD(swarf_sim_report, arcs, "c_long");
  FIELD(swarf_sim_report, tool_changes, "c_long");
  FIELD(swarf_sim_report, path_mm, "c_double");
  FIELD(swarf_sim_report, machining_s, "c_double");
  FIELD(swarf_sim_report, volume_before, "c_double");
  FIELD(swarf_sim_report, volume_after, "c_double");
  FIELD(swarf_sim_report, seconds, "c_double");
  FIELD(swarf_sim_report, alarms, "c_long");
  FIELD(swarf_sim_report, alarm_count, "c_long * 6");
  FIELD(swarf_sim_report, start, "c_double * 3");
  FIELD(swarf_sim_report, units_line, "c_long");
  FIELD(swarf_sim_report, units_missing_line, "c_long");
  FIELD(swarf_sim_report, has_deviation, "c_int");
  FIELD(swarf_sim_report, deviation, "swarf_stock_deviation");
  end();
  STRUCT(swarf_sim_progress);
  FIELD(swarf_sim_progress, fraction, "c_double");
  FIELD(swarf_sim_progress, line, "c_long");
  FIELD(swarf_sim_progress, tool, "c_int");
  FIELD(swarf_sim_progress, report, "POINTER(swarf_sim_report)");
  FIELD(swarf_sim_progress, stock, "c_void_p");
  end();
  STRUCT(swarf_line_result);
  FIELD(swarf_line_result, line, "c_long");
  FIELD(swarf_line_result, tool, "c_int");
  FIELD(swarf_line_result, moves, "c_long");
  FIELD(swarf_line_result, time_s, "c_double");
  FIELD(swarf_line_result, path_mm, "c_double");
  FIELD(swarf_line_result, removed, "c_double");
  end();
  STRUCT(swarf_sim_callbacks);
  FIELD(swarf_sim_callbacks, progress, "PROGRESS_FN");
  FIELD(swarf_sim_callbacks, alarm, "ALARM_FN");
  FIELD(swarf_sim_callbacks, line, "LINE_FN");
  FIELD(swarf_sim_callbacks, user, "c_void_p");
  end();
  STRUCT(swarf_sim_fixture); /* filled by swarf_sim_parse_fixture only */
  end();
  STRUCT(swarf_design_cache);
  FIELD(swarf_design_cache, dir, "c_char_p");
  FIELD(swarf_design_cache, off, "c_int");
  FIELD(swarf_design_cache, max_bytes, "c_longlong");
  end();
  STRUCT(swarf_sim_config);
  FIELD(swarf_sim_config, machine, "swarf_machine");
  FIELD(swarf_sim_config, stock, "swarf_sim_stock_spec");
  FIELD(swarf_sim_config, voxel, "c_double");
  FIELD(swarf_sim_config, half_width, "c_int");
  FIELD(swarf_sim_config, batch, "c_int");
  FIELD(swarf_sim_config, ntools, "c_int");
  FIELD(swarf_sim_config, line_volumes, "c_int");
  char fixtures[64];
  snprintf(fixtures, sizeof fixtures, "swarf_sim_fixture * %d", SWARF_SIM_MAX_FIXTURES);
  FIELD(swarf_sim_config, fixtures, fixtures);
  FIELD(swarf_sim_config, nfixtures, "c_int");
  FIELD(swarf_sim_config, collision_depths, "c_long");
  FIELD(swarf_sim_config, cb, "swarf_sim_callbacks");
  FIELD(swarf_sim_config, units, "c_int");
  FIELD(swarf_sim_config, offsets_file, "c_char_p");
  FIELD(swarf_sim_config, g54_set, "c_int");
  FIELD(swarf_sim_config, g54, "c_double * 3");
  FIELD(swarf_sim_config, start_set, "c_int");
  FIELD(swarf_sim_config, start, "c_double * 3");
  FIELD(swarf_sim_config, dialect, "c_int");
  FIELD(swarf_sim_config, block_delete, "c_int");
  FIELD(swarf_sim_config, subroutine_path, "c_char_p");
  FIELD(swarf_sim_config, fragment, "c_int");
  FIELD(swarf_sim_config, work_limit, "c_long");
  FIELD(swarf_sim_config, design, "c_void_p");
  FIELD(swarf_sim_config, tolerance, "c_double");
  end();
  fprintf(out, "]\n\n");
}

/* The callbacks' C types, as the module declares them with CFUNCTYPE. */
typedef int (*progress_fn)(void *, const swarf_sim_progress *);
typedef void (*alarm_fn)(void *, const swarf_alarm *);
typedef void (*line_fn)(void *, const swarf_line_result *);

static void callbacks(void) {
  swarf_sim_callbacks cb = {0};
  progress_fn p = NULL;
  alarm_fn a = NULL;
  line_fn l = NULL;
  cb.progress = p, cb.alarm = a, cb.line = l;
  (void)cb;
  fprintf(out,
          "CALLBACKS = {\n"
          "    \"PROGRESS_FN\": (\"c_int\", [\"c_void_p\", \"POINTER(swarf_sim_progress)\"]),\n"
          "    \"ALARM_FN\": (None, [\"c_void_p\", \"POINTER(swarf_alarm)\"]),\n"
          "    \"LINE_FN\": (None, [\"c_void_p\", \"POINTER(swarf_line_result)\"]),\n"
          "}\n\n");
}

static void fn(const char *name, const char *ret, const char *args) {
  fprintf(out, "    \"%s\": (%s, [%s]),\n", name, ret, args);
}

/* FN(name, ctypes result, ctypes arguments, C result, C parameter types...) */
#define FN(name, pyret, pyargs, ret, ...)                                                          \
  do {                                                                                             \
    ret (*check_)(__VA_ARGS__) = name;                                                             \
    (void)check_;                                                                                  \
    fn(#name, pyret, pyargs);                                                                      \
  } while (0)

#define P_CFG "POINTER(swarf_sim_config)"
#define P_ERR "POINTER(swarf_error)"

static void functions(void) {
  fprintf(out, "FUNCTIONS = {\n");
  FN(swarf_version, "\"c_char_p\"", "", const char *, void);
  FN(swarf_status_name, "\"c_char_p\"", "\"c_int\"", const char *, swarf_status);
  FN(swarf_status_classify, "\"c_int\"", "\"c_int\"", swarf_status_class, swarf_status);
  FN(swarf_error_format, "None", "\"" P_ERR "\", \"c_char_p\", \"c_size_t\"", void,
     const swarf_error *, char *, size_t);
  FN(swarf_sim_config_init, "None", "\"" P_CFG "\"", void, swarf_sim_config *);
  FN(swarf_sim_config_add_tool, "\"c_int\"",
     "\"" P_CFG "\", \"POINTER(swarf_sim_tool)\", \"" P_ERR "\"", swarf_status, swarf_sim_config *,
     const swarf_sim_tool *, swarf_error *);
  FN(swarf_sim_config_put_tool, "\"c_int\"",
     "\"" P_CFG "\", \"POINTER(swarf_sim_tool)\", \"" P_ERR "\"", swarf_status, swarf_sim_config *,
     const swarf_sim_tool *, swarf_error *);
  FN(swarf_sim_config_put_holder, "\"c_int\"",
     "\"" P_CFG "\", \"POINTER(swarf_sim_tool)\", \"" P_ERR "\"", swarf_status, swarf_sim_config *,
     const swarf_sim_tool *, swarf_error *);
  FN(swarf_sim_parse_holder, "\"c_int\"",
     "\"c_char_p\", \"POINTER(swarf_sim_tool)\", \"" P_ERR "\"", swarf_status, const char *,
     swarf_sim_tool *, swarf_error *);
  FN(swarf_sim_parse_fixture, "\"c_int\"",
     "\"c_char_p\", \"POINTER(swarf_sim_fixture)\", \"" P_ERR "\"", swarf_status, const char *,
     swarf_sim_fixture *, swarf_error *);
  FN(swarf_sim_config_load_tool_table, "\"c_int\"",
     "\"" P_CFG "\", \"c_char_p\", \"c_double\", \"" P_ERR "\"", swarf_status, swarf_sim_config *,
     const char *, double, swarf_error *);
  FN(swarf_sim_config_load_tool_library, "\"c_int\"", "\"" P_CFG "\", \"c_char_p\", \"" P_ERR "\"",
     swarf_status, swarf_sim_config *, const char *, swarf_error *);
  FN(swarf_sim_parse_tool, "\"c_int\"", "\"c_char_p\", \"POINTER(swarf_sim_tool)\", \"" P_ERR "\"",
     swarf_status, const char *, swarf_sim_tool *, swarf_error *);
  FN(swarf_sim_parse_stock, "\"c_int\"",
     "\"c_char_p\", \"POINTER(swarf_sim_stock_spec)\", \"" P_ERR "\"", swarf_status, const char *,
     swarf_sim_stock_spec *, swarf_error *);
  FN(swarf_machine_parse, "\"c_int\"", "\"POINTER(swarf_machine)\", \"c_char_p\", \"" P_ERR "\"",
     swarf_status, swarf_machine *, const char *, swarf_error *);
  FN(swarf_sim_new, "\"c_int\"",
     "\"" P_CFG "\", \"c_char_p\", \"POINTER(c_void_p)\", \"" P_ERR "\"", swarf_status,
     const swarf_sim_config *, const char *, swarf_sim **, swarf_error *);
  FN(swarf_sim_new_with_stock, "\"c_int\"",
     "\"" P_CFG "\", \"c_char_p\", \"c_void_p\", \"POINTER(c_void_p)\", \"" P_ERR "\"",
     swarf_status, const swarf_sim_config *, const char *, swarf_stock *, swarf_sim **,
     swarf_error *);
  FN(swarf_sim_feed, "\"c_int\"", "\"c_void_p\", \"c_char_p\", \"c_size_t\"", swarf_status,
     swarf_sim *, const char *, size_t);
  FN(swarf_sim_set_program_size, "\"c_int\"", "\"c_void_p\", \"c_longlong\"", swarf_status,
     swarf_sim *, long long);
  FN(swarf_sim_feed_file, "\"c_int\"", "\"c_void_p\", \"c_char_p\"", swarf_status, swarf_sim *,
     const char *);
  FN(swarf_sim_finish, "\"c_int\"", "\"c_void_p\"", swarf_status, swarf_sim *);
  FN(swarf_sim_error, "\"" P_ERR "\"", "\"c_void_p\"", const swarf_error *, const swarf_sim *);
  FN(swarf_sim_get_report, "\"POINTER(swarf_sim_report)\"", "\"c_void_p\"",
     const swarf_sim_report *, const swarf_sim *);
  FN(swarf_sim_stock, "\"c_void_p\"", "\"c_void_p\"", const swarf_stock *, const swarf_sim *);
  FN(swarf_sim_take_stock, "\"c_void_p\"", "\"c_void_p\"", swarf_stock *, swarf_sim *);
  FN(swarf_sim_free, "None", "\"c_void_p\"", void, swarf_sim *);
  FN(swarf_stock_read, "\"c_int\"", "\"c_char_p\", \"POINTER(c_void_p)\", \"" P_ERR "\"",
     swarf_status, const char *, swarf_stock **, swarf_error *);
  FN(swarf_stock_set_read_isolation, "None", "\"c_int\"", void, int);
  FN(swarf_stock_read_isolation, "\"c_int\"", "", int, void);
  FN(swarf_stock_free, "None", "\"c_void_p\"", void, swarf_stock *);
  FN(swarf_stock_voxel, "\"c_double\"", "\"c_void_p\"", double, const swarf_stock *);
  FN(swarf_stock_half_width, "\"c_int\"", "\"c_void_p\"", int, const swarf_stock *);
  FN(swarf_stock_volume, "\"c_double\"", "\"c_void_p\"", double, const swarf_stock *);
  FN(swarf_stock_active_voxels, "\"c_ulonglong\"", "\"c_void_p\"", unsigned long long,
     const swarf_stock *);
  FN(swarf_stock_bounds, "None", "\"c_void_p\", \"c_double * 3\", \"c_double * 3\"", void,
     const swarf_stock *, double *, double *);
  FN(swarf_stock_sample, "\"c_double\"", "\"c_void_p\", \"c_double\", \"c_double\", \"c_double\"",
     double, const swarf_stock *, double, double, double);
  FN(swarf_stock_dense_box, "None", "\"c_void_p\", \"c_int * 3\", \"c_int * 3\", \"c_double * 3\"",
     void, const swarf_stock *, int *, int *, double *);
  FN(swarf_stock_to_dense, "\"c_int\"",
     "\"c_void_p\", \"c_int * 3\", \"c_int * 3\", \"c_void_p\", \"" P_ERR "\"", swarf_status,
     const swarf_stock *, const int *, const int *, float *, swarf_error *);
  FN(swarf_stock_from_dense, "\"c_int\"",
     "\"c_double * 3\", \"c_double\", \"c_int * 3\", \"c_void_p\", \"c_int\", "
     "\"POINTER(c_void_p)\", \"" P_ERR "\"",
     swarf_status, const double *, double, const int *, const float *, int, swarf_stock **,
     swarf_error *);
  FN(swarf_stock_design_band, "\"c_int\"", "\"c_void_p\", \"c_double\", \"c_double\", \"c_int\"",
     int, const swarf_stock *, double, double, int);
  FN(swarf_sim_read_design_cached, "\"c_int\"",
     "\"c_char_p\", \"c_double\", \"c_int\", \"POINTER(swarf_design_cache)\", "
     "\"POINTER(c_void_p)\", "
     "\"POINTER(c_int)\", \"" P_ERR "\"",
     swarf_status, const char *, double, int, const swarf_design_cache *, swarf_stock **, int *,
     swarf_error *);
  FN(swarf_stock_read_design_band, "\"c_int\"",
     "\"c_char_p\", \"c_double\", \"c_int\", \"POINTER(c_void_p)\", \"" P_ERR "\"", swarf_status,
     const char *, double, int, swarf_stock **, swarf_error *);
  FN(swarf_stock_check, "\"c_int\"", "\"c_void_p\", \"" P_ERR "\"", swarf_status,
     const swarf_stock *, swarf_error *);
  FN(swarf_stock_write_vdb, "\"c_int\"", "\"c_void_p\", \"c_char_p\", \"" P_ERR "\"", swarf_status,
     const swarf_stock *, const char *, swarf_error *);
  FN(swarf_stock_write_stl, "\"c_int\"",
     "\"c_void_p\", \"c_char_p\", \"POINTER(c_size_t)\", \"" P_ERR "\"", swarf_status,
     const swarf_stock *, const char *, size_t *, swarf_error *);
  FN(swarf_stock_write_png, "\"c_int\"",
     "\"c_void_p\", \"c_char_p\", \"c_int\", \"c_int\", \"" P_ERR "\"", swarf_status,
     const swarf_stock *, const char *, int, int, swarf_error *);
  fprintf(out, "}\n\n");
}

static void constants(void) {
  fprintf(out, "CONSTANTS = {\n");
#define C(name) fprintf(out, "    \"%s\": %ld,\n", #name, (long)(name))
  C(SWARF_SIM_MAX_TOOLS);
  C(SWARF_SIM_MAX_FIXTURES);
  C(SWARF_SIM_MAX_ALARMS);
  C(SWARF_SIM_STOCK_BOX);
  C(SWARF_SIM_STOCK_CYLINDER);
  C(SWARF_ALARM_RAPID);
  C(SWARF_ALARM_SHANK);
  C(SWARF_ALARM_HOLDER);
  C(SWARF_ALARM_FIXTURE);
  C(SWARF_ALARM_GOUGE);
  C(SWARF_ALARM_NO_TOOL);
  C(SWARF_CUTTER_FLAT);
  C(SWARF_CUTTER_BALL);
  C(SWARF_CUTTER_BULL);
  C(SWARF_GCODE_UNITS_MM);
  C(SWARF_GCODE_UNITS_INCH);
  C(SWARF_CLASS_OK);
  C(SWARF_CLASS_INTERNAL);
  C(SWARF_CLASS_INPUT);
  C(SWARF_CLASS_ABORTED);
#define X(name, value, cls, msg) C(SWARF_##name);
#include "status.def"
#undef X
#undef C
  fprintf(out, "}\n");
}

int main(int argc, char **argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: swarf_pyabi OUT.py LIBRARY\n");
    return 2;
  }
  out = fopen(argv[1], "w");
  if (!out) {
    perror(argv[1]);
    return 1;
  }
  fprintf(out,
          "# _abi.py -- generated by tools/sim/python/abi.c from libswarf's headers; do not edit.\n"
          "VERSION = \"%s\"\nLIBRARY = \"%s\"\n\n",
          SWARF_VERSION_STRING, argv[2]);
  structs();
  callbacks();
  functions();
  constants();
  return fclose(out) == 0 ? 0 : 1;
}
