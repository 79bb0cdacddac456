/* Rayleigh directions with the caller's RNG, through sk_rng.
 *
 * Draws 10^6 directions about an incident direction with Frisvad's direct
 * method, histograms cos theta in 10 bins and prints each bin beside the
 * count the phase function predicts. Exits 0 when Pearson's chi^2 over the
 * bins is below the 0.1% critical value (27.88 for 9 degrees of freedom).
 *
 *   cc -std=c99 -I include c_examples/rayleigh_histogram.c \
 *      -lm target/release/libscatterkit.a -lpthread -ldl -lm
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "scatterkit.h"

/* splitmix64 (Steele, Lea, Flood 2014): the caller's generator. */
static uint64_t splitmix64(void *state) {
    uint64_t *s = (uint64_t *)state;
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

int main(void) {
    enum { BINS = 10, N = 1000000 };
    uint64_t seed = 42;
    sk_rng rng = {&seed, splitmix64};
    sk_phase rayleigh;
    const sk_vec3 w_in = {0.0f, 0.6f, 0.8f};
    long hist[BINS] = {0};
    double chi2 = 0.0, max_len_err = 0.0;
    int i;

    if (sk_phase_new_rayleigh(&rayleigh) != SK_OK) return 1;
    for (i = 0; i < N; i++) {
        sk_vec3 d;
        float mu;
        int b;
        if (sk_rayleigh_sample_dir(SK_RAYLEIGH_DIRECT, w_in, &rng, &d) != SK_OK) return 1;
        mu = d.x * w_in.x + d.y * w_in.y + d.z * w_in.z;
        b = (int)((mu + 1.0f) * 0.5f * BINS);
        hist[b < 0 ? 0 : b >= BINS ? BINS - 1 : b]++;
        max_len_err = fmax(max_len_err, fabs(sqrt(d.x * d.x + d.y * d.y + d.z * d.z) - 1.0));
    }

    printf("scatterkit %s: Rayleigh, %d directions (SK_RAYLEIGH_DIRECT)\n", sk_version(), N);
    printf("%-16s %9s %11s %9s\n", "cos theta", "observed", "expected", "pdf(mid)");
    for (i = 0; i < BINS; i++) {
        float lo = -1.0f + 2.0f * i / BINS, hi = -1.0f + 2.0f * (i + 1) / BINS;
        double expected = N * (double)(sk_phase_cdf(&rayleigh, hi) - sk_phase_cdf(&rayleigh, lo));
        double mid_pdf = sk_phase_pdf(&rayleigh, 0.5f * (lo + hi));
        chi2 += (hist[i] - expected) * (hist[i] - expected) / expected;
        printf("[%5.2f, %5.2f)   %9ld %11.1f %9.5f\n", lo, hi, hist[i], expected, mid_pdf);
    }
    printf("chi2 = %.2f (9 dof, 0.1%% critical value 27.88)\n", chi2);
    printf("max | |d| - 1 | = %.2e\n", max_len_err);
    return (chi2 < 27.88 && max_len_err < 1e-6) ? 0 : 2;
}
