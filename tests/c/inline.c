/* include/scatterkit_inline.h against the library: sk_phase_cos_inline_sample
   gives sk_phase_sample_cos's bits for every float u in [0, 1] (every
   SK_STRIDE-th float where the build sets it), for u outside [0, 1], the
   infinities and NaN (NaN for NaN), for HG phases of either sign of g, one
   below the f64 path's |g| (a call into the library) and other models.
   Prints "inline: N compared, M differ" and exits 1 on any difference. */
#include <stdio.h>
#include <string.h>

#include "scatterkit_inline.h"

#ifndef SK_STRIDE
#define SK_STRIDE 1
#endif

static unsigned long compared, differ;

static float from_bits(unsigned int b) {
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

static void check(const sk_phase *p, const sk_phase_cos_inline *c, float u, const char *what) {
    float a = sk_phase_sample_cos(p, u), b = sk_phase_cos_inline_sample(c, u);
    compared++;
    if (a != a && b != b) return;
    if (memcmp(&a, &b, sizeof a) != 0) {
        if (differ < 5) printf("%s: u = %.9g: library %.9g, inline %.9g\n", what, u, a, b);
        differ++;
    }
}

static void check_phase(const sk_phase *p, const char *what, unsigned int stride) {
    sk_phase_cos_inline c;
    unsigned int b;
    const float odd[] = {-0.0f, -1.0f, -1e-30f, 1.0000001f, 2.0f, 1e30f};
    size_t i;
    float inf = from_bits(0x7f800000u), nan = from_bits(0x7fc00000u);
    if (sk_phase_cos_inline_new(p, &c) != SK_OK) {
        printf("%s: init failed\n", what);
        differ++;
        return;
    }
    for (b = 0; b <= 0x3f800000u; b += stride) check(p, &c, from_bits(b), what);
    check(p, &c, 1.0f, what);
    for (i = 0; i < sizeof odd / sizeof odd[0]; i++) check(p, &c, odd[i], what);
    check(p, &c, inf, what);
    check(p, &c, -inf, what);
    check(p, &c, nan, what);
}

int main(void) {
    sk_phase p;
    const float gs[] = {0.7f, -0.5f, 0.999999f, -0.999f, 1e-4f, 0.0f};
    size_t i;
    for (i = 0; i < sizeof gs / sizeof gs[0]; i++) {
        char what[32];
        sprintf(what, "HG g = %g", gs[i]);
        if (sk_phase_new_hg(gs[i], &p) != SK_OK) return 1;
        /* Every float for the first, every 61st for the others. */
        check_phase(&p, what, i == 0 ? SK_STRIDE : 61u * SK_STRIDE);
    }
    sk_phase_new_rayleigh(&p);
    check_phase(&p, "Rayleigh", 61u * SK_STRIDE);
    if (sk_phase_new_fog_diameter(2.0f, &p) != SK_OK) return 1;
    check_phase(&p, "fog 2 um", 997u * SK_STRIDE);
    printf("inline: %lu compared, %lu differ (exact path %d)\n", compared, differ, SK_INLINE_EXACT);
    return differ != 0;
}
