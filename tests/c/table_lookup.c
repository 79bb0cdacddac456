/* include/scatterkit_table.h against the library: every table kind, float
 * and double, several resolutions, 2^20 + 1 evenly spaced u plus u outside
 * [0, 1], NaN and the ends, compared bit for bit with sk_table_sample_cos.
 * Compiled as C99 and as C++ by tests/c_abi/table_header.rs. Exits with the
 * number of mismatches. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scatterkit.h"
#include "scatterkit_table.h"

enum { GRID = 1 << 20, MAXN = 1000 };

static float buf[2 * (MAXN + 1)];
static double bufd[2 * (MAXN + 1)];
static long compared, mismatched;

static const float EXTRA[] = {-0.5f, 1.5f, 1e-30f, 0.99999994f, 5.9604645e-8f, 1.0f, 0.0f, -0.0f};

static void check32(const sk_table *t, float u) {
    float a = sk_table_sample_cos(t, u);
    float b = t->kind == SK_TABLE_RAYLEIGH_CDF ? sk_table_cdf_lookup(t->data, t->n, u)
                                               : sk_table_hermite_lookup(t->data, t->n, u);
    compared++;
    if (memcmp(&a, &b, sizeof a) != 0 && !(isnan(a) && isnan(b))) {
        if (mismatched++ < 5) printf("mismatch: kind %u n %lu u %.9g: %.9g vs %.9g\n", t->kind, (unsigned long)t->n, u, a, b);
    }
}

static void check64(const sk_table_f64 *t, double u) {
    double a = sk_table_sample_cos_f64(t, u);
    double b = t->kind == SK_TABLE_RAYLEIGH_CDF ? sk_table_cdf_lookup_f64(t->data, t->n, u)
                                                : sk_table_hermite_lookup_f64(t->data, t->n, u);
    compared++;
    if (memcmp(&a, &b, sizeof a) != 0 && !(isnan(a) && isnan(b))) {
        if (mismatched++ < 5) printf("mismatch f64: kind %u n %lu u %.17g: %.17g vs %.17g\n", t->kind, (unsigned long)t->n, u, a, b);
    }
}

static void sweep32(const sk_table *t) {
    long i;
    size_t k;
    for (i = 0; i <= GRID; i++) check32(t, (float)i / (float)GRID);
    for (k = 0; k < sizeof EXTRA / sizeof EXTRA[0]; k++) check32(t, EXTRA[k]);
    check32(t, (float)NAN);
}

static void sweep64(const sk_table_f64 *t) {
    long i;
    size_t k;
    for (i = 0; i <= GRID; i++) check64(t, (double)i / (double)GRID);
    for (k = 0; k < sizeof EXTRA / sizeof EXTRA[0]; k++) check64(t, (double)EXTRA[k]);
    check64(t, (double)NAN);
}

int main(void) {
    static const size_t NS[] = {1, 7, 64, 1000};
    float cx[5] = {-1.0f, -0.3f, 0.2f, 0.8f, 1.0f}, cp[5] = {0.1f, 0.3f, 0.0f, 1.5f, 4.0f};
    double cxd[5] = {-1.0, -0.3, 0.2, 0.8, 1.0}, cpd[5] = {0.1, 0.3, 0.0, 1.5, 4.0};
    sk_phase phases[3];
    sk_phase_f64 phasesd[3];
    size_t k, j;
    if (sk_phase_hg(0.7f, &phases[0]) || sk_phase_fog_diameter(2.0f, &phases[1]) ||
        sk_phase_draine(0.5f, 1.0f, &phases[2]) || sk_phase_hg_f64(-0.4, &phasesd[0]) ||
        sk_phase_fog_diameter_f64(5.0, &phasesd[1]) || sk_phase_draine_f64(0.9, 10.0, &phasesd[2])) {
        printf("constructor failed\n");
        return 1;
    }
    for (k = 0; k < sizeof NS / sizeof NS[0]; k++) {
        size_t n = NS[k];
        sk_table t;
        sk_table_f64 td;
        for (j = 0; j < 3; j++) {
            if (sk_table_inverse(&phases[j], buf, 2 * (MAXN + 1), n, &t) ||
                sk_table_inverse_f64(&phasesd[j], bufd, 2 * (MAXN + 1), n, &td)) {
                printf("table failed\n");
                return 1;
            }
            sweep32(&t);
            sweep64(&td);
        }
        if (sk_table_measured(cx, cp, 5, buf, 2 * (MAXN + 1), n, &t) ||
            sk_table_measured_f64(cxd, cpd, 5, bufd, 2 * (MAXN + 1), n, &td) ||
            0) {
            printf("measured table failed\n");
            return 1;
        }
        sweep32(&t);
        sweep64(&td);
        if (sk_table_rayleigh_cdf(buf, 2 * (MAXN + 1), n, &t) ||
            sk_table_rayleigh_cdf_f64(bufd, 2 * (MAXN + 1), n, &td)) {
            printf("cdf table failed\n");
            return 1;
        }
        sweep32(&t);
        sweep64(&td);
    }
    printf("%ld lookups compared, %ld mismatched\n", compared, mismatched);
    return mismatched != 0;
}
