/* SPDX-License-Identifier: MPL-2.0 */
/* stock_module.h -- the stock module as a shared object loaded on first use (plain C).
 *
 * Loading OpenVDB costs the dynamic loader ~60 ms of CPU at every start (its ~68,000 symbol
 * relocations), more than `swarf parse` takes to read 100,000 lines. So the `swarf` command
 * does not link the stock module: it is built as well as a shared object of its own
 * (swarf_stock-VERSION.so, linking OpenVDB; installed under LIBDIR/swarf/) exporting one
 * symbol, swarf_stock_module_table, and the command carries stock_module.c, which defines
 * every function of stock.h and stock_output.h as a call through that table, the module
 * opened (dlopen) by the first of them. Commands that never touch a stock (parse, envelope,
 * --help) never load it. libswarf (shared and static) and the tests link the module's code
 * directly, as before; the table is for the command only.
 *
 * The functions are listed once, in stock_api.def.
 */
#ifndef SWARF_STOCK_MODULE_H
#define SWARF_STOCK_MODULE_H

#include <stddef.h>

#include "stock.h"
#include "stock_output.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The module's table: its size and version (the loader refuses another build's module),
 * then one pointer per function of stock_api.def, in its order. */
typedef struct {
  size_t size;         /* sizeof(swarf_stock_module) as the module was built */
  const char *version; /* SWARF_STOCK_MODULE_VERSION as the module was built */
#define STATUS(name, params, args) swarf_status(*name) params;
#define VOID(name, params, args) void(*name) params;
#define VALUE(type, name, params, args, fallback) type(*name) params;
#include "stock_api.def"
#undef STATUS
#undef VOID
#undef VALUE
} swarf_stock_module;

/* The module's one export (stock_module_table.c). */
#define SWARF_STOCK_MODULE_SYMBOL "swarf_stock_module_table"

#ifdef __cplusplus
}
#endif

#endif
