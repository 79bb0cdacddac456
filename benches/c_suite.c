/* The media suite through the C ABI: every transmittance estimator at its
 * default (strata 0), per ray class, as a C renderer calls them. The main
 * job (examples/speed_accuracy/media_suite.rs) writes one medium and its
 * rays to the file named by SK_MEDIA_DATA, measures the same from Rust,
 * and runs this program. Prints per estimator e and class c:
 *   "suite.e.c<TAB>ns per estimate<TAB>mean per-ray variance"
 *   "suite.e.c.out<TAB>share of estimates outside [0, 1]<TAB>0"
 * Delta tracking's estimate is 1 for an escape, else 0.
 *
 * The file: uint32 n (0: the blob, through a callback), uint32 sampling
 * (0 nodes, 1 cells), float sigma_a, sigma_s per unit density, uint32
 * classes, uint32 rays per class; float density[n^3] (x fastest, over
 * [-1, 1]^3); for the blob float max[16^3], min[16^3] (its extrema); then
 * per ray float o[3], d[3] (t_max = +inf), class by class. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scatterkit.h"

enum { REPEATS = 15, PER_RAY = 100, BUDGET = 1 << 24, M = 16 };

static uint64_t splitmix(void *state) {
    uint64_t *s = (uint64_t *)state, z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static double now_ns(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e9 + t.tv_nsec;
}

/* The blob: 12 exp(-|p|^2 / 0.35^2), sigma_a : sigma_s = 1 : 4. */
static sk_coefficients blob(void *ctx, sk_vec3 p) {
    float s = 12.0f * expf(-(p.x * p.x + p.y * p.y + p.z * p.z) / (0.35f * 0.35f));
    sk_coefficients c;
    (void)ctx;
    c.sigma_a = 0.2f * s;
    c.sigma_s = 0.8f * s;
    return c;
}

static sk_medium medium;
static volatile float sink;

enum { DELTA, RATIO, RESIDUAL, MARCH, TELESCOPING, ESTIMATORS };
static const char *NAMES[] = {"delta", "ratio", "residual", "march", "telescoping"};

/* One estimate; NAN for a status other than SK_OK. */
static float estimate(int e, const float *ray, sk_rng *rng) {
    sk_track_args a;
    sk_track_result r;
    sk_status s = SK_ERR_METHOD;
    memset(&a, 0, sizeof a);
    a.medium = medium;
    a.o.x = ray[0], a.o.y = ray[1], a.o.z = ray[2];
    a.d.x = ray[3], a.d.y = ray[4], a.d.z = ray[5];
    a.t_min = 0.0f, a.t_max = INFINITY;
    a.budget = BUDGET;
    a.rng = rng;
    switch (e) {
    case DELTA:
        s = sk_delta_track(&a, &r);
        return s == SK_OK ? (r.event == SK_TRACK_ESCAPED ? 1.0f : 0.0f) : NAN;
    case RATIO:
        s = sk_ratio_track(&a, &r);
        break;
    case RESIDUAL:
        s = sk_residual_ratio_track(&a, &r);
        break;
    case MARCH:
        s = sk_ray_march(&a, &r);
        break;
    case TELESCOPING:
        s = sk_telescoping_march(&a, &r);
        break;
    }
    return s == SK_OK ? r.tr : NAN;
}

int main(void) {
    const char *path = getenv("SK_MEDIA_DATA");
    const sk_vec3 lo = {-1.0f, -1.0f, -1.0f}, hi = {1.0f, 1.0f, 1.0f};
    FILE *f = path ? fopen(path, "rb") : NULL;
    uint32_t head[2], classes, per_class, cells, c, i, k;
    float coef[2], *density = NULL, *rays, *max, *min;
    sk_grid grid;
    sk_majorants ext;
    int e;
    if (!f || fread(head, 4, 2, f) != 2 || fread(coef, 4, 2, f) != 2 || fread(&classes, 4, 1, f) != 1 ||
        fread(&per_class, 4, 1, f) != 1) {
        fprintf(stderr, "c_suite: cannot read SK_MEDIA_DATA\n");
        return 1;
    }
    cells = head[0] * head[0] * head[0];
    rays = malloc(sizeof(float) * 6 * classes * per_class);
    max = malloc(sizeof(float) * M * M * M);
    min = malloc(sizeof(float) * M * M * M);
    if (head[0] > 0) {
        density = malloc(sizeof(float) * cells);
        if (!density || fread(density, 4, cells, f) != cells) {
            fprintf(stderr, "c_suite: short grid\n");
            return 1;
        }
    } else if (!max || !min || fread(max, 4, M * M * M, f) != M * M * M || fread(min, 4, M * M * M, f) != M * M * M) {
        fprintf(stderr, "c_suite: short extrema\n");
        return 1;
    }
    if (!rays || fread(rays, 4, 6 * classes * per_class, f) != 6 * classes * per_class) {
        fprintf(stderr, "c_suite: short rays\n");
        return 1;
    }
    fclose(f);
    memset(&medium, 0, sizeof medium);
    if (head[0] > 0) {
        if (sk_grid_new(density, head[0], head[0], head[0], coef[0], coef[1], &grid) != SK_OK ||
            sk_grid_set_box(&grid, lo, hi) != SK_OK ||
            sk_grid_set_sampling(&grid, head[1] ? SK_SAMPLING_CELLS : SK_SAMPLING_NODES) != SK_OK ||
            sk_majorants_new_from_grid(&grid, M, M, M, max, min, M * M * M, &ext) != SK_OK) {
            fprintf(stderr, "c_suite: bad grid\n");
            return 1;
        }
        medium.grid = &grid;
    } else {
        if (sk_majorants_new(max, min, M, M, M, lo, hi, &ext) != SK_OK) {
            fprintf(stderr, "c_suite: bad extrema\n");
            return 1;
        }
        medium.coefficients = blob;
    }
    medium.majorants = &ext;
    for (c = 0; c < classes; c++) {
        const float *rc = rays + 6 * c * per_class;
        double best[ESTIMATORS];
        uint64_t state = 5;
        sk_rng rng = {&state, splitmix};
        /* The estimators take turns, run after run. */
        for (e = DELTA; e < ESTIMATORS; e++) {
            best[e] = INFINITY;
        }
        for (k = 0; k < REPEATS; k++) {
            for (e = DELTA; e < ESTIMATORS; e++) {
                float acc = 0.0f;
                double t0 = now_ns();
                for (i = 0; i < per_class; i++) {
                    acc += estimate(e, rc + 6 * i, &rng);
                }
                t0 = now_ns() - t0;
                sink = acc;
                best[e] = t0 < best[e] ? t0 : best[e];
            }
        }
        for (e = DELTA; e < ESTIMATORS; e++) {
            double var = 0.0;
            uint32_t out = 0;
            state = 3;
            for (i = 0; i < per_class; i++) {
                double s = 0.0, s2 = 0.0, mean;
                for (k = 0; k < PER_RAY; k++) {
                    float t = estimate(e, rc + 6 * i, &rng);
                    s += t, s2 += (double)t * t;
                    out += !(t >= 0.0f && t <= 1.0f);
                }
                mean = s / PER_RAY;
                var += fmax(s2 - PER_RAY * mean * mean, 0.0) / (PER_RAY - 1);
            }
            printf("suite.%s.%u\t%.2f\t%.6e\n", NAMES[e], c, best[e] / per_class, var / per_class);
            printf("suite.%s.%u.out\t%.6f\t0\n", NAMES[e], c, (double)out / (per_class * PER_RAY));
        }
    }
    return 0;
}
