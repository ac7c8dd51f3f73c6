/* SPDX-License-Identifier: MPL-2.0 */
/* stl_box.h -- boxes as STL files for the stock tests (header only): the 12
 * triangles of an axis-aligned box, outward, written binary or ASCII, and
 * damaged on purpose (a triangle left out, one doubled, one flipped). */
#ifndef SWARF_TESTS_STOCK_STL_BOX_H
#define SWARF_TESTS_STOCK_STL_BOX_H

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "stock.h"

/* Corners of each face, counter-clockwise seen from outside (bits x, y, z). */
static const int stl_box_faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                        {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};

/* The box's triangles: tri[t][corner][k]. */
static inline void stl_box_triangles(const double lo[3], const double hi[3], float tri[12][3][3]) {
  for (int f = 0; f < 6; f++)
    for (int h = 0; h < 2; h++) {
      const int idx[3] = {stl_box_faces[f][0], stl_box_faces[f][1 + h], stl_box_faces[f][2 + h]};
      for (int c = 0; c < 3; c++)
        for (int k = 0; k < 3; k++)
          tri[2 * f + h][c][k] = (float)((idx[c] >> k) & 1 ? hi[k] : lo[k]);
    }
}

/* A box stock, NULL on failure. */
static inline swarf_stock *test_box_(const double lo[3], const double hi[3], double voxel,
                                     int half_width) {
  swarf_stock *s = NULL;
  return swarf_stock_new_box(lo, hi, voxel, half_width, &s, NULL) == SWARF_OK ? s : NULL;
}

enum { STL_GOOD = 0, STL_OPEN, STL_NONMANIFOLD, STL_FLIPPED };

/* Write the box (damaged as `how` says); ascii 1 for an ASCII STL. */
static inline int stl_box_write(const char *path, const double lo[3], const double hi[3], int ascii,
                                int how) {
  float tri[13][3][3];
  int n = 12;
  FILE *f = fopen(path, "wb");
  if (f == NULL) return -1;
  stl_box_triangles(lo, hi, tri);
  if (how == STL_OPEN) n = 11;
  if (how == STL_NONMANIFOLD) memcpy(tri[12], tri[0], sizeof tri[0]), n = 13;
  if (how == STL_FLIPPED) {
    float t[3];
    memcpy(t, tri[0][1], sizeof t), memcpy(tri[0][1], tri[0][2], sizeof t),
        memcpy(tri[0][2], t, sizeof t);
  }
  if (ascii) {
    fprintf(f, "solid box\n");
    for (int i = 0; i < n; i++) {
      fprintf(f, "  facet normal 0 0 0\n    outer loop\n");
      for (int c = 0; c < 3; c++)
        fprintf(f, "      vertex %.9g %.9g %.9g\n", tri[i][c][0], tri[i][c][1], tri[i][c][2]);
      fprintf(f, "    endloop\n  endfacet\n");
    }
    fprintf(f, "endsolid box\n");
  } else {
    unsigned char head[84] = {0};
    uint32_t count = (uint32_t)n;
    memcpy(head + 80, &count, 4); /* little-endian hosts */
    fwrite(head, 1, 84, f);
    for (int i = 0; i < n; i++) {
      float rec[12] = {0};
      unsigned char attr[2] = {0, 0};
      memcpy(rec + 3, tri[i], 9 * sizeof(float));
      fwrite(rec, sizeof(float), 12, f);
      fwrite(attr, 1, 2, f);
    }
  }
  return fclose(f);
}

#endif
