/* SPDX-License-Identifier: MPL-2.0 */
/* stock_module.c -- the `swarf` command's stock module loader (stock_module.h): every function
 * of stock.h and stock_output.h, each a call through the table of swarf_stock-VERSION.so,
 * which the first of them opens (once, whichever thread calls first). The module is, the
 * first that loads of:
 *   $SWARF_STOCK_MODULE                      when set (then only it);
 *   SWARF_STOCK_MODULE_REL from the folder of the running executable (installed: bin/swarf
 *     and LIBDIR/swarf/; the build tree mirrors it: build/tools/swarf, build/lib/swarf/);
 *   beside the executable (a copy of swarf with its module);
 *   SWARF_STOCK_MODULE_BUILT, where the build put it (a copy of swarf alone).
 * Built into the command only. */
#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "stock_module.h"

#define MODULE_FILE "swarf_stock-" SWARF_STOCK_MODULE_VERSION ".so"

static pthread_once_t module_once = PTHREAD_ONCE_INIT;
static const swarf_stock_module *module;
static char module_error[2 * PATH_MAX + 512];

/* dst (cap bytes): the folder of the running executable, then "/" rel. 0 on failure. */
static int exe_relative(char *dst, size_t cap, const char *rel) {
  char exe[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n <= 0) return 0;
  exe[n] = '\0';
  char *slash = strrchr(exe, '/');
  if (!slash) return 0;
  *slash = '\0';
  return snprintf(dst, cap, "%s/%s", exe, rel) < (int)cap;
}

/* The table of the module at path, or NULL with the reason in module_error. */
static const swarf_stock_module *module_try(const char *path) {
  void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    snprintf(module_error, sizeof module_error, "cannot load the stock module (%s)", dlerror());
    return NULL;
  }
  const swarf_stock_module *m = dlsym(h, SWARF_STOCK_MODULE_SYMBOL);
  if (!m || m->size != sizeof(swarf_stock_module) ||
      strcmp(m->version, SWARF_STOCK_MODULE_VERSION) != 0) {
    snprintf(module_error, sizeof module_error,
             "the stock module %s is not the one of this swarf %s (another build?)", path,
             SWARF_STOCK_MODULE_VERSION);
    dlclose(h);
    return NULL;
  }
  return m;
}

static void module_open(void) {
  char path[PATH_MAX], first[sizeof module_error] = "";
  const char *env = getenv("SWARF_STOCK_MODULE");
  if (env != NULL && env[0] != '\0') {
    module = module_try(env);
    return;
  }
  if (exe_relative(path, sizeof path, SWARF_STOCK_MODULE_REL) && (module = module_try(path)))
    return;
  snprintf(first, sizeof first, "%s", module_error);
  if (exe_relative(path, sizeof path, MODULE_FILE) && (module = module_try(path))) return;
  if ((module = module_try(SWARF_STOCK_MODULE_BUILT))) return;
  snprintf(module_error, sizeof module_error, "%s; swarf is not installed whole",
           first[0] ? first : "cannot find the running executable's folder");
}

/* The table, the module opened on the first call; NULL (module_error says why) if it cannot
 * be. */
static const swarf_stock_module *module_get(void) {
  pthread_once(&module_once, module_open);
  return module;
}

#define STATUS(name, params, args)                                                                 \
  swarf_status name params {                                                                       \
    const swarf_stock_module *m = module_get();                                                    \
    if (!m) return swarf_error_set(err, SWARF_ERR_IO, "%s", module_error);                         \
    return m->name args;                                                                           \
  }
#define VOID(name, params, args)                                                                   \
  void name params {                                                                               \
    const swarf_stock_module *m = module_get();                                                    \
    if (m) m->name args;                                                                           \
  }
#define VALUE(type, name, params, args, fallback)                                                  \
  type name params {                                                                               \
    const swarf_stock_module *m = module_get();                                                    \
    return m ? m->name args : (fallback);                                                          \
  }
#include "stock_api.def"
#undef STATUS
#undef VOID
#undef VALUE
