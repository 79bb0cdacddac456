/* What the slab benchmarks share (benches/c_flight.c, benches/c_photon.c):
 * xoshiro256++ behind sk_rng, a clock, the distance to the slab's
 * boundary, and MCML's HG inverse and direction update (Wang, Jacques &
 * Zheng 1995), the formulas a photon code writes itself. The slab is
 * z in [0, 1]; photons enter at z = 0 along +z. */
#ifndef SK_BENCH_SLAB_H
#define SK_BENCH_SLAB_H

#include <math.h>
#include <stdint.h>
#include <time.h>

/* xoshiro256++. */
typedef struct {
    uint64_t s[4];
} xo;
static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
static uint64_t xo_next(void *state) {
    uint64_t *s = ((xo *)state)->s;
    uint64_t r = rotl(s[0] + s[3], 23) + s[0], t = s[1] << 17;
    s[2] ^= s[0], s[3] ^= s[1], s[1] ^= s[2], s[0] ^= s[3], s[2] ^= t, s[3] = rotl(s[3], 45);
    return r;
}
static double xo_u(xo *x) { return (double)(xo_next(x) >> 11) * 0x1p-53; }
/* The state from a seed, by SplitMix64. */
static xo xo_seed(uint64_t seed) {
    xo x;
    int i;
    for (i = 0; i < 4; i++) {
        uint64_t z = (seed += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        x.s[i] = z ^ (z >> 31);
    }
    return x;
}

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The distance to the slab's boundary along a direction of z component dz
   from height z. */
static double to_boundary(double z, double dz) {
    if (dz > 0.0) return (1.0 - z) / dz;
    if (dz < 0.0) return -z / dz;
    return 1e30;
}

/* MCML's HG inverse for asymmetry g and its direction update of d; always
   inlined, as a code's own scattering step is, however many of a
   benchmark's loops call it (with two callers gcc had left it out of line
   and moved every inline loop's time). */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void mcml_scatter(double d[3], double g, xo *x) {
    double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xo_u(x));
    double ct = (1.0 + g * g - s * s) / (2.0 * g), st = sqrt(fmax(0.0, 1.0 - ct * ct));
    double phi = 2.0 * 3.14159265358979323846 * xo_u(x), cp = cos(phi), sp = sin(phi);
    double ux = d[0], uy = d[1], uz = d[2];
    if (fabs(uz) > 0.99999) {
        d[0] = st * cp, d[1] = st * sp, d[2] = uz > 0.0 ? ct : -ct;
    } else {
        double t = sqrt(1.0 - uz * uz);
        d[0] = st * (ux * uz * cp - uy * sp) / t + ux * ct;
        d[1] = st * (uy * uz * cp + ux * sp) / t + uy * ct;
        d[2] = -st * cp * t + uz * ct;
    }
}

#endif /* SK_BENCH_SLAB_H */
