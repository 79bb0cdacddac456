/* One tracking call per flight, as MCML-style slab codes make them: the
 * photon's own loop decides absorption and scattering, and asks the library
 * only where the next collision is (one call per flight, a short ray to the
 * slab's boundary). A slab z in [0, 1] of optical depth tau = 2 (sigma_t = 2),
 * albedo 0.9 (the photon's weight times 0.9 at each collision, Russian
 * roulette below 1e-4), HG g = 0.75 by the textbook inverse inline,
 * index-matched boundaries, 10^6 photons entering at z = 0 along +z.
 *
 * Modes (argv[1]; all run when none is given or it is "all"; argv[2], if
 * given, the number of photons):
 *   cb64     sk_delta_track_f64 through a callback medium with one majorant
 *   cb32     the same in float (sk_delta_track)
 *   cbratio  cb64 plus a ratio-tracking estimate of the transmittance to
 *            the boundary along each new direction (an exit estimator)
 *   grid64   sk_delta_track_f64 through a 1 x 1 x 64 density grid
 *   grid32   the same in float (sk_delta_track through an sk_grid)
 *   free64   sk_free_path_f64 (no tracking call): the floor
 *   cb64z    cb64 with the argument struct zeroed and filled at every call
 *            (the other modes fill it once and change the ray per flight)
 * Each prints "mode seconds ns_per_photon R T"; R and T (the reflected and
 * transmitted weight per photon) agree between modes within their noise
 * (the modes draw their uniforms differently: a grid walk draws afresh in
 * each cell), and between the two libraries to the digits printed, which
 * checks that they do the same work.
 *
 * The current API takes an argument struct: the modes keep one per medium
 * and write only the ray (o, d, t_max) per flight, as the media guide
 * advises; cb64z zeroes all 160 bytes at every call instead, which gcc -O2
 * compiles to rep stosq, and measures what that costs.
 *
 * Built against the current C API by default, or against the 0.1 API
 * (commit 950c067, per-estimator functions) with -DSK_API_0_1, so that one
 * file times both libraries: scripts/flight_vs_0_1.sh builds both and runs
 * them alternately. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scatterkit.h"
#include "slab.h"

#define PHOTONS_DEFAULT 1000000
static long PHOTONS = PHOTONS_DEFAULT;
#define SIGMA_T 2.0
#define ALBEDO 0.9
#define G 0.75
#define NZ 64

/* The medium as the code's callback: sigma_t = 2 everywhere (the code asks
   for scattering only and decides absorption itself). */
#ifdef SK_API_0_1
static double sigma_t64(void *ctx, sk_vec3_f64 p) { (void)ctx, (void)p; return SIGMA_T; }
static float sigma_t32(void *ctx, sk_vec3 p) { (void)ctx, (void)p; return (float)SIGMA_T; }
#else
static sk_coefficients_f64 coef64(void *ctx, sk_vec3_f64 p) {
    sk_coefficients_f64 c = {0.0, SIGMA_T};
    (void)ctx, (void)p;
    return c;
}
static sk_coefficients coef32(void *ctx, sk_vec3 p) {
    sk_coefficients c = {0.0f, (float)SIGMA_T};
    (void)ctx, (void)p;
    return c;
}
#endif

enum mode { CB64, CB32, CBRATIO, GRID64, FREE64, CB64Z, GRID32, MODES };
static const char *NAMES[MODES] = {"cb64", "cb32", "cbratio", "grid64", "free64", "cb64z", "grid32"};

static sk_grid_f64 grid;
static sk_grid grid32;
static double density[NZ];
static float density32[NZ];

/* One flight from (x, y, z) along d to the boundary at distance t_max: the
   distance to the next collision (>= t_max: none). */
static double flight(enum mode m, const double o[3], const double d[3], double t_max, sk_rng *rng,
                     xo *x) {
    double t = t_max;
    uint32_t ev = 0;
    sk_vec3_f64 o64 = {o[0], o[1], o[2]}, d64 = {d[0], d[1], d[2]};
    sk_vec3 o32 = {(float)o[0], (float)o[1], (float)o[2]}, d32 = {(float)d[0], (float)d[1], (float)d[2]};
    float t32 = 0.0f;
    switch (m) {
    case FREE64:
        t = sk_free_path_f64(SIGMA_T, xo_u(x));
        return t;
#ifdef SK_API_0_1
    case CB64:
    case CB64Z:
    case CBRATIO:
        if (sk_delta_track_fn_f64(sigma_t64, NULL, SIGMA_T, o64, d64, 0.0, t_max, rng, &t, &ev)) exit(3);
        return ev == SK_TRACK_ESCAPED ? t_max : t;
    case CB32:
        if (sk_delta_track_fn(sigma_t32, NULL, (float)SIGMA_T, o32, d32, 0.0f, (float)t_max, rng, &t32, &ev))
            exit(3);
        return ev == SK_TRACK_ESCAPED ? t_max : (double)t32;
    case GRID64:
        if (sk_delta_track_f64(&grid, o64, d64, t_max, rng, &t, &ev)) exit(3);
        return ev == SK_TRACK_ESCAPED ? t_max : t;
    case GRID32:
        if (sk_delta_track(&grid32, o32, d32, (float)t_max, rng, &t32, &ev)) exit(3);
        return ev == SK_TRACK_ESCAPED ? t_max : (double)t32;
#else
    case CB64:
    case CBRATIO:
    case GRID64: {
        /* The medium's arguments, filled once; the ray per flight. */
        static sk_track_args_f64 cb, gr;
        sk_track_args_f64 *a = m == GRID64 ? &gr : &cb;
        sk_track_result_f64 r;
        if (a->rng == NULL) {
            memset(a, 0, sizeof *a);
            if (m == GRID64) {
                a->medium.grid = &grid;
            } else {
                a->medium.coefficients = coef64;
                a->medium.sigma_maj = SIGMA_T;
            }
            a->rng = rng;
        }
        a->o = o64, a->d = d64, a->t_max = t_max;
        if (sk_delta_track_f64(a, &r)) exit(3);
        return r.event == SK_TRACK_ESCAPED ? t_max : r.t;
    }
    case CB64Z: {
        /* Zeroed and filled at every call. */
        sk_track_args_f64 a;
        sk_track_result_f64 r;
        memset(&a, 0, sizeof a);
        a.medium.coefficients = coef64;
        a.medium.sigma_maj = SIGMA_T;
        a.o = o64, a.d = d64, a.t_max = t_max, a.rng = rng;
        if (sk_delta_track_f64(&a, &r)) exit(3);
        return r.event == SK_TRACK_ESCAPED ? t_max : r.t;
    }
    case GRID32: {
        static sk_track_args a;
        sk_track_result r;
        if (a.rng == NULL) {
            memset(&a, 0, sizeof a);
            a.medium.grid = &grid32;
            a.rng = rng;
        }
        a.o = o32, a.d = d32, a.t_max = (float)t_max;
        if (sk_delta_track(&a, &r)) exit(3);
        return r.event == SK_TRACK_ESCAPED ? t_max : (double)r.t;
    }
    case CB32: {
        static sk_track_args a;
        sk_track_result r;
        if (a.rng == NULL) {
            memset(&a, 0, sizeof a);
            a.medium.coefficients = coef32;
            a.medium.sigma_maj = (float)SIGMA_T;
            a.rng = rng;
        }
        a.o = o32, a.d = d32, a.t_max = (float)t_max;
        if (sk_delta_track(&a, &r)) exit(3);
        (void)t32;
        return r.event == SK_TRACK_ESCAPED ? t_max : (double)r.t;
    }
#endif
    default:
        (void)o32, (void)d32, (void)t32, (void)ev;
        exit(2);
    }
}

/* The transmittance to the boundary along d by ratio tracking (the exit
   estimator of mode cbratio). */
static double exit_estimate(const double o[3], const double d[3], double t_max, sk_rng *rng) {
    sk_vec3_f64 o64 = {o[0], o[1], o[2]}, d64 = {d[0], d[1], d[2]};
#ifdef SK_API_0_1
    return sk_ratio_track_fn_f64(sigma_t64, NULL, SIGMA_T, o64, d64, 0.0, t_max, rng);
#else
    static sk_track_args_f64 a;
    sk_track_result_f64 r;
    if (a.rng == NULL) {
        memset(&a, 0, sizeof a);
        a.medium.coefficients = coef64;
        a.medium.sigma_maj = SIGMA_T;
        a.rng = rng;
    }
    a.o = o64, a.d = d64, a.t_max = t_max;
    if (sk_ratio_track_f64(&a, &r)) exit(3);
    return r.tr;
#endif
}

static void run(enum mode m, uint64_t seed) {
    /* Static: the argument structs filled once keep pointing at them. */
    static xo state;
    static sk_rng rng;
    double r_w = 0.0, t_w = 0.0, exits = 0.0, t0, secs;
    long i;
    state = xo_seed(seed);
    rng.state = &state;
    rng.next_u64 = xo_next;
    t0 = now_s();
    for (i = 0; i < PHOTONS; i++) {
        double o[3] = {0.0, 0.0, 0.0}, d[3] = {0.0, 0.0, 1.0}, w = 1.0;
        for (;;) {
            double tb = to_boundary(o[2], d[2]), t = flight(m, o, d, tb, &rng, &state);
            if (t >= tb) {
                if (d[2] > 0.0)
                    t_w += w;
                else
                    r_w += w;
                break;
            }
            o[0] += t * d[0], o[1] += t * d[1], o[2] += t * d[2];
            w *= ALBEDO;
            if (w < 1e-4) {
                if (xo_u(&state) < 0.1)
                    w *= 10.0;
                else
                    break;
            }
            mcml_scatter(d, G, &state);
            if (m == CBRATIO) exits += w * exit_estimate(o, d, to_boundary(o[2], d[2]), &rng);
        }
    }
    secs = now_s() - t0;
    printf("%s %.4f %.1f %.8f %.8f", NAMES[m], secs, 1e9 * secs / PHOTONS, r_w / PHOTONS, t_w / PHOTONS);
    if (m == CBRATIO) printf(" exit %.6f", exits / PHOTONS);
    printf("\n");
}

int main(int argc, char **argv) {
    int k;
    for (k = 0; k < NZ; k++) density[k] = 1.0, density32[k] = 1.0f;
    if (argc > 2) PHOTONS = atol(argv[2]);
    if (PHOTONS <= 0) return 2;
#ifdef SK_API_0_1
    if (sk_grid_new_f64(density, 1, 1, NZ, 0.0, SIGMA_T, &grid)) return 4;
#else
    if (sk_grid_new_f64(density, 1, 1, NZ, 0.0, SIGMA_T, &grid)) return 4;
#endif
    if (sk_grid_new(density32, 1, 1, NZ, 0.0f, (float)SIGMA_T, &grid32)) return 4;
    {
        /* The grid spans the slab, and far beyond it sideways. */
        sk_vec3_f64 lo = {-1e6, -1e6, 0.0}, hi = {1e6, 1e6, 1.0};
        sk_vec3 lo32 = {-1e6f, -1e6f, 0.0f}, hi32 = {1e6f, 1e6f, 1.0f};
        if (sk_grid_set_box_f64(&grid, lo, hi)) return 4;
        if (sk_grid_set_box(&grid32, lo32, hi32)) return 4;
    }
    for (k = 0; k < MODES; k++) {
        if (argc > 1 && strcmp(argv[1], "all") != 0 && strcmp(argv[1], NAMES[k]) != 0) continue;
        run((enum mode)k, 42);
    }
    return 0;
}
