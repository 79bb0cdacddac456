/* One translation unit of a program of four (two C, two C++), each
 * including scatterkit_portable.h: the header defines nothing with external
 * linkage, so they link. Built once per unit with -DUNIT_NAME=<name>; the
 * unit built with -DPORTABLE_UNIT_MAIN also holds main, which calls the
 * other three and compares their values with its own. */
#include "scatterkit_portable.h"

#ifdef __cplusplus
#define UNIT_API extern "C"
#else
#define UNIT_API
#endif

UNIT_API float unit_c1(float u);
UNIT_API float unit_c2(float u);
UNIT_API float unit_cpp1(float u);
UNIT_API float unit_cpp2(float u);

/* This unit's value: the Rayleigh table, HG and the Dirac limit. */
UNIT_API float UNIT_NAME(float u) {
    skp_hg h, d;
    skp_hg_new(0.5f, &h);
    skp_hg_new(1.0f, &d);
    return skp_rayleigh_sample_cos(u) + skp_hg_sample_cos(h, u) + skp_hg_sample_cos(d, u);
}

#ifdef PORTABLE_UNIT_MAIN
#include <stdio.h>
int main(void) {
    float (*units[4])(float);
    int i, bad = 0;
    units[0] = unit_c1;
    units[1] = unit_c2;
    units[2] = unit_cpp1;
    units[3] = unit_cpp2;
    for (i = 0; i < 4; i++) {
        float u = 0.1f + 0.2f * (float)i;
        bad += units[i](u) != UNIT_NAME(u);
    }
    printf("four units: %d of 4 agree\n", 4 - bad);
    return bad;
}
#endif
