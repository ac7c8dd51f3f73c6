/* SPDX-License-Identifier: MPL-2.0 */
/* html_assets.c -- the files the --html page inlines, embedded at build
 * time (NUL-terminated): the page's template and viewer (tools/cli/html/)
 * and Debian's three.js with its OrbitControls (libjs-three), paths given by
 * CMake. Without three.js (SWARF_THREE_JS unset) --html is refused. */
#ifdef SWARF_THREE_JS
#define EMBED(name, file)                                                                          \
  __asm__(".section .rodata\n.global " #name "\n.type " #name ", @object\n" #name                  \
          ":\n.incbin \"" file "\"\n.byte 0\n.previous\n")
EMBED(swarf_html_page_text, SWARF_HTML_DIR "/page.html");
EMBED(swarf_html_viewer, SWARF_HTML_DIR "/viewer.js");
EMBED(swarf_html_three, SWARF_THREE_JS);
EMBED(swarf_html_orbit, SWARF_ORBIT_JS);
const int swarf_html_built = 1;
#else
const char swarf_html_page_text[] = "", swarf_html_viewer[] = "", swarf_html_three[] = "",
           swarf_html_orbit[] = "";
const int swarf_html_built = 0;
#endif
