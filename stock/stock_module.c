/* stock_module.c -- the `swarf` command's stock module loader (stock_module.h): every function
 * of stock.h and stock_output.h, each a call through the table of swarf_stock-VERSION.so,
 * which the first of them opens (once, whichever thread calls first). The module is looked
 * for at SWARF_STOCK_MODULE_REL from the folder of the running executable (the build tree
 * mirrors the installed layout: bin/swarf and LIBDIR/swarf/). Built into the command only. */
#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "stock_module.h"

static pthread_once_t module_once = PTHREAD_ONCE_INIT;
static const swarf_stock_module *module;
static char module_error[PATH_MAX + 512];

/* PATH_MAX bytes of dst: the folder of the running executable, then rel. 0 on failure. */
static int module_path(char *dst, size_t cap, const char *rel) {
  char exe[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n <= 0) return 0;
  exe[n] = '\0';
  char *slash = strrchr(exe, '/');
  if (!slash) return 0;
  *slash = '\0';
  return snprintf(dst, cap, "%s/%s", exe, rel) < (int)cap;
}

static void module_open(void) {
  char path[PATH_MAX];
  if (!module_path(path, sizeof path, SWARF_STOCK_MODULE_REL)) {
    snprintf(module_error, sizeof module_error,
             "the stock module: cannot find the running executable's folder");
    return;
  }
  void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    snprintf(module_error, sizeof module_error,
             "cannot load the stock module (%s): swarf is not installed whole", dlerror());
    return;
  }
  const swarf_stock_module *m = dlsym(h, SWARF_STOCK_MODULE_SYMBOL);
  if (!m || m->size != sizeof(swarf_stock_module) ||
      strcmp(m->version, SWARF_STOCK_MODULE_VERSION) != 0) {
    snprintf(module_error, sizeof module_error,
             "the stock module %s is not the one of this swarf %s (another build?)", path,
             SWARF_STOCK_MODULE_VERSION);
    dlclose(h);
    return;
  }
  module = m;
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
