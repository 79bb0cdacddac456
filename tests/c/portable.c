/* The portable tier on the CPU: every case of portable_cases.h over its 2^24
 * indices (every stride-th with a stride argument), hashed per block of 2^16
 * indices (FNV-1a over the output bits, every NaN as 0x7fc00000: its sign
 * and payload are not specified), one line per block:
 * "case block hash". tests/c_abi/portable.rs compares them with the Rust
 * module's. */
#include <stdio.h>
#include <stdlib.h>

#include "portable_cases.h"

int main(int argc, char **argv) {
    unsigned long stride = argc > 1 ? strtoul(argv[1], NULL, 10) : 1ul;
    int c, i;
    skp_u32 b, k;
    float o[4], maj[PC_MAJ_N];
    for (k = 0; k < PC_MAJ_N; k++) {
        maj[k] = pc_maj(k);
    }
    for (c = 0; c < PC_CASES; c++) {
        for (b = 0; b < PC_N >> 16; b++) {
            skp_u32 h = 2166136261u;
            for (k = b << 16; k < (b + 1u) << 16; k += (skp_u32)stride) {
                pc_case(c, k, maj, o);
                for (i = 0; i < 4; i++) {
                    skp_u32 w = skp_bits(o[i]);
                    w = (w & 0x7fffffffu) > 0x7f800000u ? 0x7fc00000u : w;
                    h = (h ^ w) * 16777619u;
                }
            }
            printf("%d %u %08x\n", c, (unsigned)b, (unsigned)h);
        }
    }
    return 0;
}
