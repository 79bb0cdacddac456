/* A slab of fog traced with delta tracking and phase sampling.
 *
 * A plane-parallel slab 0 <= z <= 1 of optical thickness 2 holds 2 um fog
 * droplets (sk_phase_new_fog_diameter). Photons enter at z = 0 along +z; the
 * medium is the caller's coefficients (sigma_a, sigma_s: constant inside
 * the slab), so the library's delta tracking finds each collision and says
 * whether it scatters (with the fog phase function) or absorbs. Prints
 * the transmitted, reflected and absorbed shares for albedo 0.9 and for a
 * purely absorbing slab; the latter must transmit exp(-2) within 4 standard
 * deviations, and the three shares must add to 1. Exits 0 when they do.
 *
 *   cc -std=c99 -I include c_examples/fog_slab.c \
 *      -lm target/release/libscatterkit.a -lpthread -ldl -lm
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "scatterkit.h"

static uint64_t splitmix64(void *state) {
    uint64_t *s = (uint64_t *)state;
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static float uniform(sk_rng *rng) { return (float)(rng->next_u64(rng->state) >> 40) * (1.0f / 16777216.0f); }

/* The slab: sigma_t and the albedo inside, nothing outside. */
typedef struct {
    float sigma_t, albedo;
} slab;

static sk_coefficients slab_coefficients(void *ctx, sk_vec3 p) {
    const slab *s = (const slab *)ctx;
    sk_coefficients c = {0.0f, 0.0f};
    if (p.z >= 0.0f && p.z <= 1.0f) {
        c.sigma_s = s->sigma_t * s->albedo;
        c.sigma_a = s->sigma_t - c.sigma_s;
    }
    return c;
}

enum { TRANSMITTED, REFLECTED, ABSORBED, OUTCOMES };

/* One photon's fate; -1 on a library error. */
static int trace(const sk_phase *fog, float sigma_t, float albedo, sk_rng *rng) {
    sk_vec3 p = {0.0f, 0.0f, 0.0f}, w = {0.0f, 0.0f, 1.0f};
    slab s;
    sk_track_args a;
    sk_track_result r;
    int bounce;
    s.sigma_t = sigma_t, s.albedo = albedo;
    memset(&a, 0, sizeof a); /* no flags, the default budget */
    a.medium.coefficients = slab_coefficients;
    a.medium.ctx = &s;
    a.medium.sigma_maj = sigma_t; /* one majorant: the slab's sigma_t */
    a.rng = rng;
    for (bounce = 0; bounce < 100000; bounce++) {
        /* The segment to the slab's face ahead (finite: a medium given by
         * a callback has no box of its own to leave). */
        a.o = p, a.d = w;
        a.t_max = w.z > 0.0f ? (1.0f - p.z) / w.z : w.z < 0.0f ? -p.z / w.z : 1e30f;
        if (sk_delta_track(&a, &r) != SK_OK) return -1;
        if (r.event == SK_TRACK_ESCAPED) return w.z > 0.0f ? TRANSMITTED : REFLECTED;
        if (r.event == SK_TRACK_ABSORBED) return ABSORBED;
        p.x += r.t * w.x;
        p.y += r.t * w.y;
        p.z += r.t * w.z;
        w = sk_phase_sample_dir(fog, w, uniform(rng), uniform(rng), NULL);
    }
    return -1;
}

int main(void) {
    enum { N = 200000 };
    const float sigma_t = 2.0f, albedos[2] = {0.9f, 0.0f};
    uint64_t seed = 2024;
    sk_rng rng = {&seed, splitmix64};
    sk_phase fog;
    int k, ok = 1;

    if (sk_phase_new_fog_diameter(2.0f, &fog) != SK_OK) return 1;
    printf("fog slab: 2 um droplets, optical thickness %.1f, normal incidence, %d photons\n", sigma_t, N);
    for (k = 0; k < 2; k++) {
        long count[OUTCOMES] = {0, 0, 0};
        int i;
        for (i = 0; i < N; i++) {
            int outcome = trace(&fog, sigma_t, albedos[k], &rng);
            if (outcome < 0) return 1;
            count[outcome]++;
        }
        printf("albedo %.1f: transmitted %.4f  reflected %.4f  absorbed %.4f\n", albedos[k],
               (double)count[TRANSMITTED] / N, (double)count[REFLECTED] / N, (double)count[ABSORBED] / N);
        ok &= count[TRANSMITTED] + count[REFLECTED] + count[ABSORBED] == N;
        if (albedos[k] == 0.0f) {
            double p = exp(-sigma_t), share = (double)count[TRANSMITTED] / N;
            double sd = sqrt(p * (1.0 - p) / N);
            printf("  absorbing only: transmitted %.5f, exp(-tau) = %.5f, |difference| = %.1f sigma\n", share, p,
                   fabs(share - p) / sd);
            ok &= fabs(share - p) <= 4.0 * sd && count[REFLECTED] == 0;
        }
    }
    printf("%s\n", ok ? "ok" : "FAILED");
    return ok ? 0 : 2;
}
