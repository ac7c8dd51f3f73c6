/* SPDX-License-Identifier: MPL-2.0 */
/* sanitize_options.c -- the sanitizers' defaults in a SWARF_SANITIZE build.
 *
 * Linked into every executable of such a build (swarf_target_options in the
 * top CMakeLists.txt), never into a library: ASan and UBSan read these before
 * their environment variables (ASAN_OPTIONS, UBSAN_OPTIONS), which still win.
 * A report stops the program with SIGABRT (never a plain exit status that a
 * test expecting a failure could take for the one it wants), LeakSanitizer
 * included; UBSan is also compiled without recovery (-fno-sanitize-recover).
 */
#define SWARF_SANITIZE_DEFAULT __attribute__((visibility("default"), used))

SWARF_SANITIZE_DEFAULT const char *__asan_default_options(void);
SWARF_SANITIZE_DEFAULT const char *__ubsan_default_options(void);

const char *__asan_default_options(void) {
  return "halt_on_error=1:abort_on_error=1:detect_leaks=1:"
         "check_initialization_order=1";
}

const char *__ubsan_default_options(void) {
  return "halt_on_error=1:abort_on_error=1:print_stacktrace=1";
}
