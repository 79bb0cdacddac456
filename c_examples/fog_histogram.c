/* The fog phase function from a droplet diameter.
 *
 * Builds Jendersie & d'Eon's fitted fog phase function for 2 um droplets,
 * samples 10^6 directions about an incident direction with the caller's RNG
 * (uniforms converted as the library does: top 24 bits), and prints a
 * histogram of the scattering angle beside what the phase function predicts.
 * Bins are in theta (the lobe is narrow), and the expected counts come from
 * sk_phase_cdf. Exits 0 when Pearson's chi^2 is below the 0.1% critical value
 * for 17 degrees of freedom (40.79).
 *
 *   cc -std=c99 -I include c_examples/fog_histogram.c \
 *      -lm target/release/libscatterkit.a -lpthread -ldl -lm
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "scatterkit.h"

static uint64_t splitmix64(uint64_t *s) {
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static float uniform(uint64_t *s) { return (float)(splitmix64(s) >> 40) * (1.0f / 16777216.0f); }

int main(void) {
    enum { BINS = 18, N = 1000000 };
    const double pi = 3.14159265358979323846;
    /* Bin edges in degrees: fine where the forward lobe is. */
    const double edges[BINS + 1] = {0, 1, 2, 4, 6, 8, 10, 15, 20, 30, 40, 50, 60, 80, 100, 120, 140, 160, 180};
    const sk_vec3 w_in = {0.6f, 0.0f, -0.8f};
    long hist[BINS] = {0};
    uint64_t seed = 7;
    sk_phase fog;
    double chi2 = 0.0;
    int i, b;

    if (sk_phase_new_fog_diameter(2.0f, &fog) != SK_OK) return 1;
    for (i = 0; i < N; i++) {
        float pdf;
        sk_vec3 d = sk_phase_sample_dir(&fog, w_in, uniform(&seed), uniform(&seed), &pdf);
        double c = d.x * w_in.x + d.y * w_in.y + d.z * w_in.z;
        double theta = acos(c > 1.0 ? 1.0 : c < -1.0 ? -1.0 : c) * 180.0 / pi;
        for (b = 0; b < BINS - 1 && theta >= edges[b + 1]; b++) {
        }
        hist[b]++;
    }
    printf("fog, 2 um droplets: mean cos theta %.4f, %d directions\n", sk_phase_mean_cosine(&fog), N);
    printf("%-14s %9s %11s %12s\n", "theta (deg)", "observed", "expected", "pdf(lo)/sr");
    for (b = 0; b < BINS; b++) {
        float c_hi = (float)cos(edges[b] * pi / 180.0), c_lo = (float)cos(edges[b + 1] * pi / 180.0);
        double expected = N * (double)(sk_phase_cdf(&fog, c_hi) - sk_phase_cdf(&fog, c_lo));
        chi2 += (hist[b] - expected) * (hist[b] - expected) / expected;
        printf("[%5.1f, %5.1f)  %9ld %11.1f %12.5f\n", edges[b], edges[b + 1], hist[b], expected,
               (double)sk_phase_pdf(&fog, c_hi));
    }
    printf("chi2 = %.2f (17 dof, 0.1%% critical value 40.79)\n", chi2);
    return chi2 < 40.79 ? 0 : 2;
}
