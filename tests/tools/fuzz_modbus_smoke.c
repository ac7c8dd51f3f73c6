/* SPDX-License-Identifier: MPL-2.0 */
/* fuzz_modbus_smoke.c -- a plain driver for the Modbus fuzz entry
 * (fuzz_modbus.c), no libFuzzer needed: it runs the entry on well-formed
 * requests of every function code (TCP and RTU, good and bad addresses,
 * counts, units and command values), then on `-n` deterministic mutations
 * of them (byte flips, truncations, extensions, splices) for at most `-t`
 * seconds. A breach of the entry's checks aborts (and ASan/UBSan builds
 * catch memory errors). Usage: fuzz_modbus_smoke [-n N] [-t SECONDS]
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint64_t rng = 0x2545F4914F6CDD1Dull;
static unsigned next(void) {
  rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
  return (unsigned)(rng >> 32);
}

/* A seed: backend byte, then one length-prefixed frame. */
static size_t seed(uint8_t *out, int tcp, int unit, const uint8_t *pdu, size_t n) {
  size_t at = 0, len = tcp ? 7 + n : 1 + n + 2;
  out[at++] = tcp ? 0 : 1;
  out[at++] = (uint8_t)len;
  if (tcp) {
    const uint8_t head[7] = {0x12, 0x34, 0, 0, 0, (uint8_t)(n + 1), (uint8_t)unit};
    memcpy(out + at, head, 7), at += 7;
  } else {
    out[at++] = (uint8_t)unit;
  }
  memcpy(out + at, pdu, n), at += n;
  if (!tcp) out[at++] = 0xAA, out[at++] = 0x55; /* CRC (not checked past libmodbus) */
  return at;
}

static const uint8_t pdus[][12] = {{4, 0, 0, 0, 20},
                                   {3, 0, 0, 0, 65},
                                   {3, 0, 64, 0, 1},
                                   {4, 0, 60, 0, 10},
                                   {2, 0, 0, 0, 7},
                                   {1, 0, 0, 0, 1},
                                   {6, 0, 64, 0, 1},
                                   {6, 0, 64, 0, 9},
                                   {6, 0, 3, 0, 1},
                                   {0x11},
                                   {16, 0, 64, 0, 1, 2, 0, 2},
                                   {16, 0, 0, 0, 2, 4, 0, 1, 0, 2},
                                   {4, 0, 0, 0, 200},
                                   {0x17, 0, 0, 0, 2, 0, 64, 0, 1, 2, 0, 3},
                                   {0x16, 0, 64, 0, 0, 0, 1},
                                   {0x2B, 0x0E, 1, 0}};
static const size_t lens[] = {5, 5, 5, 5, 5, 5, 5, 5, 5, 1, 8, 10, 5, 12, 7, 4};

int main(int argc, char **argv) {
  long n = 100000;
  double limit = 5.0;
  uint8_t seeds[128][300], buf[600];
  size_t sizes[128], ns = 0;
  clock_t t0 = clock();
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!strcmp(argv[i], "-n")) n = atol(argv[i + 1]);
    if (!strcmp(argv[i], "-t")) limit = atof(argv[i + 1]);
  }
  for (size_t p = 0; p < sizeof lens / sizeof lens[0]; p++)
    for (int tcp = 0; tcp <= 1; tcp++)
      for (int unit = 0; unit <= 2; unit += 1)
        sizes[ns] = seed(seeds[ns], tcp, unit, pdus[p], lens[p]), ns++;
  for (size_t i = 0; i < ns; i++)
    LLVMFuzzerTestOneInput(seeds[i], sizes[i]);
  for (long k = 0; k < n && (double)(clock() - t0) / CLOCKS_PER_SEC < limit; k++) {
    size_t i = next() % ns, m = sizes[i];
    memcpy(buf, seeds[i], m);
    switch (next() % 4) {
    case 0:
      for (int f = 0, nf = 1 + next() % 4; f < nf; f++)
        buf[1 + next() % (m - 1)] ^= (uint8_t)(1u << (next() % 8));
      break;
    case 1:
      m = 2 + next() % (m - 1);
      break;
    case 2:
      for (size_t add = next() % 40; add-- && m < sizeof buf;)
        buf[m++] = (uint8_t)next();
      break;
    default: {
      size_t j = next() % ns;
      memcpy(buf + m, seeds[j] + 1, sizes[j] - 1), m += sizes[j] - 1; /* two frames */
    }
    }
    LLVMFuzzerTestOneInput(buf, m);
  }
  printf("fuzz_modbus_smoke: %zu seeds and their mutations passed\n", ns);
  return 0;
}
