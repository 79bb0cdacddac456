/* Media and mixtures through the C ABI, per call, as a C path tracer makes
 * the calls: the main job (examples/speed_accuracy/c_media.rs) writes a
 * density grid and a set of rays to the file named by SK_MEDIA_DATA, times
 * the same estimators from Rust on the same rays, and runs this program to
 * time them from C. Prints "key<TAB>ns<TAB>0" lines (ns per ray or per
 * sample, the fastest of REPEATS runs). The main job runs it three times,
 * taking turns with its Rust runs, and keeps the fastest of each.
 *
 * The file: uint32 n, uint32 rays, float density[n^3] (x fastest, over
 * [-1, 1]^3, sigma_a 0.2, sigma_s 0.8 per unit density), then per ray
 * float o[3], d[3] (t_max = +inf). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scatterkit.h"

enum { REPEATS = 15, BUDGET = 1 << 24 };

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

static sk_grid grid;
static sk_majorants ext; /* majorants with minorants */
static sk_vec3 *orig, *dir;
static uint32_t n_rays;
static volatile float sink;

enum estimator { DELTA, RATIO, RESIDUAL, MARCH };
static const char *NAMES[] = {"delta", "ratio", "residual", "march"};

/* One estimate along ray i; its t or transmittance. */
static float estimate(enum estimator e, sk_vec3 o, sk_vec3 d, sk_rng *rng) {
    sk_track_args a;
    sk_track_result r;
    memset(&a, 0, sizeof a);
    a.medium.grid = &grid;
    a.medium.majorants = &ext;
    a.o = o, a.d = d, a.t_min = 0.0f, a.t_max = INFINITY;
    a.budget = BUDGET;
    a.strata = 0; /* the library's choice */
    a.rng = rng;
    switch (e) {
    case DELTA:
        return sk_delta_track(&a, &r) == SK_OK ? r.t : NAN;
    case RATIO:
        return sk_ratio_track(&a, &r) == SK_OK ? r.tr : NAN;
    case RESIDUAL:
        return sk_residual_ratio_track(&a, &r) == SK_OK ? r.tr : NAN;
    case MARCH:
        return sk_ray_march(&a, &r) == SK_OK ? r.tr : NAN;
    }
    return NAN;
}

/* ns per ray over every ray for each estimator, the fastest of REPEATS
 * runs, the estimators taking turns. */
static void per_ray(double best[4]) {
    int k, e;
    uint32_t i;
    for (e = DELTA; e <= MARCH; e++) {
        best[e] = INFINITY;
    }
    for (k = 0; k < REPEATS; k++) {
        for (e = DELTA; e <= MARCH; e++) {
            uint64_t state = 7;
            sk_rng rng = {&state, splitmix};
            float acc = 0.0f;
            double t0 = now_ns();
            for (i = 0; i < n_rays; i++) {
                acc += estimate((enum estimator)e, orig[i], dir[i], &rng);
            }
            t0 = now_ns() - t0;
            sink = acc;
            if (t0 < best[e]) {
                best[e] = t0;
            }
        }
    }
    for (e = DELTA; e <= MARCH; e++) {
        best[e] /= n_rays;
    }
}

/* ns per call of a ray that misses the box. */
static double miss(enum estimator e) {
    const sk_vec3 o = {3.0f, 3.0f, 3.0f}, d = {1.0f, 0.0f, 0.0f};
    double best = INFINITY;
    int k, i, calls = 100000;
    for (k = 0; k < REPEATS; k++) {
        uint64_t state = 7;
        sk_rng rng = {&state, splitmix};
        float acc = 0.0f;
        double t0 = now_ns();
        for (i = 0; i < calls; i++) {
            acc += estimate(e, o, d, &rng);
        }
        t0 = now_ns() - t0;
        sink = acc;
        if (t0 < best) {
            best = t0;
        }
    }
    return best / calls;
}

/* The exact inverse of Rayleigh + HG 0.7 + fog 2 um (0.5 : 0.3 : 0.2), ns
 * per sample. */
static double mixture_exact(void) {
    sk_phase ray, hg, fog;
    sk_mixture mix;
    double best = INFINITY;
    int k, i, calls = 1 << 14;
    sk_phase_new_rayleigh(&ray);
    sk_phase_new_hg(0.7f, &hg);
    sk_phase_new_fog_diameter(2.0f, &fog);
    {
        sk_mixture_part parts[3] = {{&ray, NULL, 0.5f}, {&hg, NULL, 0.3f}, {&fog, NULL, 0.2f}};
        if (sk_mixture_new(parts, 3, &mix) != SK_OK) {
            return NAN;
        }
    }
    for (k = 0; k < REPEATS; k++) {
        float acc = 0.0f;
        double t0 = now_ns();
        for (i = 0; i < calls; i++) {
            acc += sk_mixture_sample_cos(&mix, (i + 0.5f) / calls);
        }
        t0 = now_ns() - t0;
        sink = acc;
        if (t0 < best) {
            best = t0;
        }
    }
    return best / calls;
}

int main(void) {
    const char *path = getenv("SK_MEDIA_DATA");
    const uint32_t resolutions[] = {16, 64, 128};
    FILE *f = path ? fopen(path, "rb") : NULL;
    uint32_t n, cells, r, i;
    float *density, *rays;
    int e;
    if (!f || fread(&n, 4, 1, f) != 1 || fread(&n_rays, 4, 1, f) != 1) {
        fprintf(stderr, "c_media: cannot read SK_MEDIA_DATA\n");
        return 1;
    }
    cells = n * n * n;
    density = malloc(sizeof(float) * cells);
    rays = malloc(sizeof(float) * 6 * n_rays);
    orig = malloc(sizeof(sk_vec3) * n_rays);
    dir = malloc(sizeof(sk_vec3) * n_rays);
    if (!density || !rays || !orig || !dir || fread(density, 4, cells, f) != cells ||
        fread(rays, 4, 6 * n_rays, f) != 6 * n_rays) {
        fprintf(stderr, "c_media: short SK_MEDIA_DATA\n");
        return 1;
    }
    fclose(f);
    for (i = 0; i < n_rays; i++) {
        sk_vec3 o = {rays[6 * i], rays[6 * i + 1], rays[6 * i + 2]};
        sk_vec3 d = {rays[6 * i + 3], rays[6 * i + 4], rays[6 * i + 5]};
        orig[i] = o;
        dir[i] = d;
    }
    {
        const sk_vec3 lo = {-1.0f, -1.0f, -1.0f}, hi = {1.0f, 1.0f, 1.0f};
        if (sk_grid_new(density, n, n, n, 0.2f, 0.8f, &grid) != SK_OK ||
            sk_grid_set_box(&grid, lo, hi) != SK_OK) {
            fprintf(stderr, "c_media: bad grid\n");
            return 1;
        }
    }
    for (r = 0; r < 3; r++) {
        uint32_t m = resolutions[r], len = m * m * m;
        float *max = malloc(sizeof(float) * len), *min = malloc(sizeof(float) * len);
        if (!max || !min || sk_majorants_new_from_grid(&grid, m, m, m, max, min, len, &ext) != SK_OK) {
            fprintf(stderr, "c_media: extrema at %u failed\n", m);
            return 1;
        }
        {
            double best[4];
            per_ray(best);
            for (e = DELTA; e <= MARCH; e++) {
                printf("media.%s.%u\t%.2f\t0\n", NAMES[e], m, best[e]);
                printf("miss.%s.%u\t%.2f\t0\n", NAMES[e], m, miss((enum estimator)e));
            }
        }
        free(max);
        free(min);
    }
    {
        /* The miss with one majorant cell: what the cost of a call owes to
           the size of the majorant grid (nothing, where it is checked once). */
        float max1[1], min1[1];
        if (sk_majorants_new_from_grid(&grid, 1, 1, 1, max1, min1, 1, &ext) != SK_OK) {
            fprintf(stderr, "c_media: extrema at 1 failed\n");
            return 1;
        }
        for (e = DELTA; e <= MARCH; e++) {
            printf("miss.%s.1\t%.2f\t0\n", NAMES[e], miss((enum estimator)e));
        }
    }
    printf("mix_exact\t%.2f\t0\n", mixture_exact());
    return 0;
}
