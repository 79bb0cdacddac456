/* Mie scattering by a cloud droplet, sampled through a table.
 *
 * Solves a water droplet of 10 um diameter in air at 550 nm (m = 1.333 +
 * 1e-8 i) into a buffer this program owns (the library never allocates),
 * tabulates its phase function at the angles sk_mie_tabulate_f64 chooses (crowded
 * into the forward peak, about 1/x radians wide), inverts that into a table
 * (sk_table_new_measured_f64, sizes from sk_mie_table_len_f64), samples 10^6
 * directions, and prints a histogram of the scattering angle beside what the
 * Mie phase function predicts (sk_mie_pdf_f64 integrated over each bin by
 * Simpson's rule). Exits 0 when Pearson's chi^2 is below the 0.1% critical
 * value for 18 degrees of freedom (42.31).
 *
 *   cc -std=c99 -I include c_examples/mie_cloud.c \
 *      -lm target/release/libscatterkit.a -lpthread -ldl -lm
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "scatterkit.h"

static uint64_t splitmix64(uint64_t *s) {
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/* A uniform in [0, 1) from the top 53 bits. */
static double uniform(uint64_t *s) { return (double)(splitmix64(s) >> 11) * 0x1p-53; }

/* 2 pi * integral of the phase function over theta in [a, b] (radians). */
static double bin_probability(const sk_mie_f64 *sphere, double a, double b) {
    const int steps = 2000; /* even */
    double h = (b - a) / steps, sum = 0.0;
    int k;
    for (k = 0; k <= steps; k++) {
        double t = a + k * h, w = (k == 0 || k == steps) ? 1.0 : (k % 2 ? 4.0 : 2.0);
        sum += w * sk_mie_pdf_f64(sphere, cos(t)) * sin(t);
    }
    return 2.0 * 3.14159265358979323846 * sum * h / 3.0;
}

int main(void) {
    enum { BINS = 19, N = 1000000 };
    const double pi = 3.14159265358979323846;
    const double edges[BINS + 1] = {0, 0.5, 1, 2, 3, 4, 6, 8, 10, 15, 20, 30, 45, 60, 90, 120, 140, 160, 170, 180};
    const sk_complex_f64 water = {1.333, 1e-8};
    const sk_vec3_f64 w_in = {0.0, 0.6, 0.8};
    double x = sk_mie_size_parameter_f64(10.0, 0.55, 1.0), chi2 = 0.0, *cos_theta, *pdf, *data;
    size_t len = sk_mie_len_f64(x, water), angles, intervals;
    sk_complex_f64 *buf = malloc(len * sizeof *buf);
    long hist[BINS] = {0};
    uint64_t seed = 11;
    sk_mie_f64 sphere;
    sk_table_f64 table;
    int i, b;

    if (!buf || sk_mie_new_f64(x, water, buf, len, &sphere) != SK_OK) return 1;
    if (sk_mie_table_len_f64(x, &angles, &intervals) != SK_OK) return 1;
    cos_theta = malloc(angles * sizeof *cos_theta);
    pdf = malloc(angles * sizeof *pdf);
    data = malloc(sk_table_len(SK_TABLE_MEASURED, intervals) * sizeof *data);
    if (!cos_theta || !pdf || !data) return 1;
    if (sk_mie_tabulate_f64(&sphere, cos_theta, pdf, angles) != SK_OK) return 1;
    if (sk_table_new_measured_f64(cos_theta, pdf, angles, data, sk_table_len(SK_TABLE_MEASURED, intervals),
                              intervals, &table) != SK_OK)
        return 1;
    printf("Mie, 10 um water droplet at 550 nm: x = %.2f, %zu terms, Q_ext = %.5f, Q_sca = %.5f, g = %.5f\n", x,
           sphere.terms, sphere.efficiencies.q_ext, sphere.efficiencies.q_sca, sphere.efficiencies.g);
    printf("table: %zu angles, %zu intervals; %d directions\n", angles, intervals, N);

    for (i = 0; i < N; i++) {
        double p;
        sk_vec3_f64 d = sk_table_sample_dir_f64(&table, w_in, uniform(&seed), uniform(&seed), &p);
        double c = d.x * w_in.x + d.y * w_in.y + d.z * w_in.z;
        double theta = acos(c > 1.0 ? 1.0 : c < -1.0 ? -1.0 : c) * 180.0 / pi;
        for (b = 0; b < BINS - 1 && theta >= edges[b + 1]; b++) {
        }
        hist[b]++;
    }
    printf("theta (deg)       sampled    expected\n");
    for (b = 0; b < BINS; b++) {
        double expected = N * bin_probability(&sphere, edges[b] * pi / 180.0, edges[b + 1] * pi / 180.0);
        chi2 += (hist[b] - expected) * (hist[b] - expected) / expected;
        printf("[%5.1f, %5.1f)  %9ld  %10.1f\n", edges[b], edges[b + 1], hist[b], expected);
    }
    printf("chi^2 = %.2f with %d degrees of freedom (0.1%% critical value 42.31): %s\n", chi2, BINS - 1,
           chi2 < 42.31 ? "consistent" : "INCONSISTENT");
    free(buf);
    free(cos_theta);
    free(pdf);
    free(data);
    return chi2 < 42.31 ? 0 : 1;
}
