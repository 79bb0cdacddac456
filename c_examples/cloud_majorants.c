/* A cloud traced through a majorant grid, beside one global majorant.
 *
 * A 64^3 density grid over the box [-1, 1]^3 holds a cloud: a dense core
 * and a thin haze (at most 5 % of the peak) with empty corners. Rays from
 * random points on a sphere around the box aim at random points inside it.
 * For each ray, ratio tracking estimates the transmittance and delta
 * tracking finds the first collision, once walking 16^3 local majorants
 * (sk_majorants_new_from_grid, pbrt-v4's default resolution) and once with a 1^3
 * majorant grid, which is the classic single global majorant. Prints the
 * mean transmittance of both (they must agree: both are unbiased) and the
 * tentative collisions (density evaluations) per ray, the cost the local
 * majorants cut. Exits 0 when the means agree within 4 standard errors
 * and the local majorants need fewer evaluations.
 *
 *   cc -std=c99 -I include c_examples/cloud_majorants.c \
 *      -lm target/release/libscatterkit.a -lpthread -ldl -lm
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scatterkit.h"

enum { N = 64, RAYS = 20000 };

static uint64_t splitmix64(void *state) {
    uint64_t *s = (uint64_t *)state;
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/* The cloud at lattice node (i, j, k): a Gaussian core of peak 40 and a
 * haze of at most 2 (5 %), empty where x + y + z is large. */
static float cloud(int i, int j, int k) {
    float x = 2.0f * i / (N - 1) - 1.0f, y = 2.0f * j / (N - 1) - 1.0f, z = 2.0f * k / (N - 1) - 1.0f;
    float r2 = (x - 0.1f) * (x - 0.1f) + (y + 0.2f) * (y + 0.2f) + 2.0f * z * z;
    float haze = 1.0f + sinf(5.0f * x) * cosf(4.0f * y) * sinf(3.0f * z);
    if (x + y + z > 1.5f) return 0.0f;
    return 40.0f * expf(-r2 / 0.04f) + haze;
}

typedef struct {
    double tr_sum, tr_sq, steps_ratio, steps_delta;
    long collided;
} tally;

int main(void) {
    static float density[N * N * N];
    float store16[16 * 16 * 16], store1[1];
    sk_grid grid;
    sk_majorants local, global;
    sk_vec3 lo = {-1, -1, -1}, hi = {1, 1, 1};
    uint64_t seed = 2026;
    sk_rng rng = {&seed, splitmix64};
    tally t[2] = {{0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}};
    const sk_majorants *maj[2];
    int i, j, k, r, m;
    for (k = 0; k < N; k++)
        for (j = 0; j < N; j++)
            for (i = 0; i < N; i++) density[i + N * (j + N * k)] = cloud(i, j, k);
    if (sk_grid_new(density, N, N, N, 0.2f, 0.8f, &grid) || sk_grid_set_box(&grid, lo, hi) ||
        sk_majorants_new_from_grid(&grid, 16, 16, 16, store16, NULL, sk_majorant_len(16, 16, 16), &local) ||
        sk_majorants_new_from_grid(&grid, 1, 1, 1, store1, NULL, 1, &global)) {
        fprintf(stderr, "building the medium failed\n");
        return 1;
    }
    maj[0] = &local;
    maj[1] = &global;
    for (r = 0; r < RAYS; r++) {
        /* A point on the sphere of radius 3 and a target inside the box. */
        float zc = 2.0f * sk_uniform(&rng) - 1.0f, ph = 6.2831853f * sk_uniform(&rng);
        float s = sqrtf(1.0f - zc * zc);
        sk_vec3 o = {3.0f * s * cosf(ph), 3.0f * s * sinf(ph), 3.0f * zc};
        sk_vec3 aim = {1.6f * sk_uniform(&rng) - 0.8f, 1.6f * sk_uniform(&rng) - 0.8f,
                       1.6f * sk_uniform(&rng) - 0.8f};
        sk_vec3 d = {aim.x - o.x, aim.y - o.y, aim.z - o.z};
        for (m = 0; m < 2; m++) {
            /* One argument struct for every estimator: the medium (a grid
             * here) and its bounds, the ray, the budget, the generator. */
            sk_track_args a;
            sk_track_result rr, tk;
            memset(&a, 0, sizeof a); /* no flags, the default budget */
            a.medium.grid = &grid;
            a.medium.majorants = maj[m];
            a.o = o, a.d = d, a.t_min = 0.0f, a.t_max = INFINITY;
            a.budget = 1u << 24;
            a.rng = &rng;
            if (sk_ratio_track(&a, &rr) || sk_delta_track(&a, &tk)) {
                fprintf(stderr, "tracking failed\n");
                return 1;
            }
            t[m].tr_sum += rr.tr;
            t[m].tr_sq += (double)rr.tr * rr.tr;
            t[m].steps_ratio += rr.steps;
            t[m].steps_delta += tk.steps;
            t[m].collided += tk.event != SK_TRACK_ESCAPED;
        }
    }
    printf("majorants   mean transmittance      evaluations per ray (ratio, delta)   collided\n");
    for (m = 0; m < 2; m++) {
        double mean = t[m].tr_sum / RAYS, var = t[m].tr_sq / RAYS - mean * mean;
        printf("%-10s  %.4f +- %.4f       %8.1f  %8.1f                        %.4f\n",
               m ? "global 1^3" : "local 16^3", mean, sqrt(var / RAYS), t[m].steps_ratio / RAYS,
               t[m].steps_delta / RAYS, (double)t[m].collided / RAYS);
    }
    {
        double m0 = t[0].tr_sum / RAYS, m1 = t[1].tr_sum / RAYS;
        double v0 = (t[0].tr_sq / RAYS - m0 * m0) / RAYS, v1 = (t[1].tr_sq / RAYS - m1 * m1) / RAYS;
        double fewer = t[1].steps_ratio / t[0].steps_ratio;
        printf("local majorants: %.1fx fewer density evaluations for ratio tracking, %.1fx for delta tracking\n",
               fewer, t[1].steps_delta / t[0].steps_delta);
        if (fabs(m0 - m1) <= 4.0 * sqrt(v0 + v1) && fewer > 1.0) {
            printf("ok\n");
            return 0;
        }
    }
    printf("FAILED\n");
    return 1;
}
