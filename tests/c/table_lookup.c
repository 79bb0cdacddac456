/* include/scatterkit_table.h against the library, bit for bit, float and
 * double, several resolutions: every 1-D table kind at 2^22 + 1 evenly
 * spaced u plus u outside [0, 1], NaN and the ends, against
 * sk_table_sample_cos; 2-D tables with slices of both Hermite kinds
 * (inverse CDFs of phase functions, measured phase functions) on a grid of
 * 2049 x (beyond both ends too) by 2049 u, plus NaN and infinite x,
 * against sk_table2d_sample_cos. At least 10^7 lookups per kind and
 * precision. Compiled as C99 and as C++ by tests/c_abi/table_header.rs.
 * Exits with the number of mismatches. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scatterkit.h"
#include "scatterkit_table.h"

enum { GRID = 1 << 22, MAXN = 1000, K2 = 4, GRID2 = 2048 };

static float buf[2 * (MAXN + 1)];
static double bufd[2 * (MAXN + 1)];
static float buf2[K2 * 2 * (MAXN + 1)];
static double buf2d[K2 * 2 * (MAXN + 1)];
static long compared, mismatched, compared2d[2];

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

static void check2d32(const sk_table2d *t, float x, float u, int kind) {
    float a = sk_table2d_sample_cos(t, x, u);
    float b = sk_table2d_lookup(t->data, t->n, t->k, t->x0, t->dx, x, u);
    compared++;
    compared2d[kind]++;
    if (memcmp(&a, &b, sizeof a) != 0 && !(isnan(a) && isnan(b))) {
        if (mismatched++ < 5) printf("mismatch 2-D: n %lu x %.9g u %.9g: %.9g vs %.9g\n", (unsigned long)t->n, x, u, a, b);
    }
}

static void check2d64(const sk_table2d_f64 *t, double x, double u, int kind) {
    double a = sk_table2d_sample_cos_f64(t, x, u);
    double b = sk_table2d_lookup_f64(t->data, t->n, t->k, t->x0, t->dx, x, u);
    compared++;
    compared2d[kind]++;
    if (memcmp(&a, &b, sizeof a) != 0 && !(isnan(a) && isnan(b))) {
        if (mismatched++ < 5) printf("mismatch 2-D f64: n %lu x %.17g u %.17g: %.17g vs %.17g\n", (unsigned long)t->n, x, u, a, b);
    }
}

/* x from x0 - 0.2 range to x0 + 1.2 range on GRID2 + 1 points, each with
 * GRID2 + 1 values of u; then NaN and infinite x. */
static void sweep2d32(const sk_table2d *t, int kind) {
    long i, j;
    float range = t->dx * (float)(t->k - 1), xs[3] = {(float)NAN, (float)INFINITY, -(float)INFINITY};
    for (i = 0; i <= GRID2; i++) {
        float x = t->x0 + range * (-0.2f + 1.4f * (float)i / (float)GRID2);
        for (j = 0; j <= GRID2; j++) check2d32(t, x, (float)j / (float)GRID2, kind);
    }
    for (i = 0; i < 3; i++) check2d32(t, xs[i], 0.5f, kind);
    check2d32(t, t->x0, (float)NAN, kind);
}

static void sweep2d64(const sk_table2d_f64 *t, int kind) {
    long i, j;
    double range = t->dx * (double)(t->k - 1), xs[3] = {(double)NAN, (double)INFINITY, -(double)INFINITY};
    for (i = 0; i <= GRID2; i++) {
        double x = t->x0 + range * (-0.2 + 1.4 * (double)i / (double)GRID2);
        for (j = 0; j <= GRID2; j++) check2d64(t, x, (double)j / (double)GRID2, kind);
    }
    for (i = 0; i < 3; i++) check2d64(t, xs[i], 0.5, kind);
    check2d64(t, t->x0, (double)NAN, kind);
}

/* 2-D tables of resolutions 7, 64 and 1000: from K2 phase functions
 * (kind 0) and from K2 measured phase functions written slice by slice
 * (kind 1). Returns nonzero if a constructor fails. */
static int tables2d(const sk_phase *phases, const sk_phase_f64 *phasesd) {
    static const size_t NS2[] = {7, 64, 1000};
    float cx[3] = {-1.0f, 0.1f, 1.0f}, cp[3] = {0.2f, 0.0f, 3.0f};
    double cxd[3] = {-1.0, 0.1, 1.0}, cpd[3] = {0.2, 0.0, 3.0};
    size_t k, j;
    for (k = 0; k < sizeof NS2 / sizeof NS2[0]; k++) {
        size_t n = NS2[k], per = 2 * (n + 1), len = sk_table2d_len(n, K2);
        sk_table2d t;
        sk_table2d_f64 td;
        if (sk_table2d_new_inverse(phases, K2, buf2, len, n, 0.4f, 0.1f, &t) ||
            sk_table2d_new_inverse_f64(phasesd, K2, buf2d, len, n, 380.0, 25.0, &td))
            return 1;
        sweep2d32(&t, 0);
        sweep2d64(&td, 0);
        for (j = 0; j < K2; j++) {
            sk_table s;
            sk_table_f64 sd;
            cp[1] = 0.5f * (float)j;
            cpd[1] = 0.7 * (double)j;
            if (sk_table_new_measured(cx, cp, 3, buf2 + j * per, per, n, &s) ||
                sk_table_new_measured_f64(cxd, cpd, 3, buf2d + j * per, per, n, &sd))
                return 1;
        }
        if (sk_table2d_new(buf2, len, n, K2, -1.0f, 0.5f, &t) ||
            sk_table2d_new_f64(buf2d, len, n, K2, 2.0, 0.3, &td))
            return 1;
        sweep2d32(&t, 1);
        sweep2d64(&td, 1);
    }
    return 0;
}

int main(void) {
    static const size_t NS[] = {1, 7, 64, 1000};
    float cx[5] = {-1.0f, -0.3f, 0.2f, 0.8f, 1.0f}, cp[5] = {0.1f, 0.3f, 0.0f, 1.5f, 4.0f};
    double cxd[5] = {-1.0, -0.3, 0.2, 0.8, 1.0}, cpd[5] = {0.1, 0.3, 0.0, 1.5, 4.0};
    float cq[5] = {0.0f, 0.0f, 2.0f, 0.0f, 0.0f};
    double cqd[5] = {0.0, 0.0, 2.0, 0.0, 0.0};
    sk_phase phases[4];
    sk_phase_f64 phasesd[4];
    size_t k, j;
    if (sk_phase_new_hg(0.7f, &phases[0]) || sk_phase_new_fog_diameter(2.0f, &phases[1]) ||
        sk_phase_new_draine(0.5f, 1.0f, &phases[2]) || sk_phase_new_hg_f64(-0.4, &phasesd[0]) ||
        sk_phase_new_fog_diameter_f64(5.0, &phasesd[1]) || sk_phase_new_draine_f64(0.9, 10.0, &phasesd[2]) ||
        sk_phase_new_rayleigh(&phases[3]) || sk_phase_new_hg_f64(0.95, &phasesd[3])) {
        printf("constructor failed\n");
        return 1;
    }
    for (k = 0; k < sizeof NS / sizeof NS[0]; k++) {
        size_t n = NS[k];
        sk_table t;
        sk_table_f64 td;
        for (j = 0; j < 3; j++) {
            if (sk_table_new_inverse(&phases[j], buf, 2 * (MAXN + 1), n, &t) ||
                sk_table_new_inverse_f64(&phasesd[j], bufd, 2 * (MAXN + 1), n, &td)) {
                printf("table failed\n");
                return 1;
            }
            sweep32(&t);
            sweep64(&td);
        }
        if (sk_table_new_measured(cx, cp, 5, buf, 2 * (MAXN + 1), n, &t) ||
            sk_table_new_measured_f64(cxd, cpd, 5, bufd, 2 * (MAXN + 1), n, &td) ||
            0) {
            printf("measured table failed\n");
            return 1;
        }
        sweep32(&t);
        sweep64(&td);
        /* A support inside (-1, 1), from -0.3 to 0.8: the cubic's rounding
           near either end must not pass it. */
        if (sk_table_new_measured(cx, cq, 5, buf, 2 * (MAXN + 1), n, &t) ||
            sk_table_new_measured_f64(cxd, cqd, 5, bufd, 2 * (MAXN + 1), n, &td)) {
            printf("measured table failed\n");
            return 1;
        }
        sweep32(&t);
        sweep64(&td);
        if (sk_table_new_rayleigh_cdf(buf, 2 * (MAXN + 1), n, &t) ||
            sk_table_new_rayleigh_cdf_f64(bufd, 2 * (MAXN + 1), n, &td)) {
            printf("cdf table failed\n");
            return 1;
        }
        sweep32(&t);
        sweep64(&td);
    }
    if (tables2d(phases, phasesd)) {
        printf("2-D table failed\n");
        return 1;
    }
    printf("2-D: %ld lookups of tables of phase functions, %ld of measured ones\n", compared2d[0], compared2d[1]);
    printf("%ld lookups compared, %ld mismatched\n", compared, mismatched);
    return mismatched != 0;
}
