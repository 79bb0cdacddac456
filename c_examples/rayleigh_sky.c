/* The polarised sky of a Rayleigh atmosphere, by a vector Monte Carlo.
 *
 * A plane-parallel layer of optical thickness 0.5 over a black ground, lit
 * by the Sun at mu0 = 0.2 (flux pi per unit area normal to the beam). Each
 * photon scatters with the exact polarisation-dependent sampler
 * (sk_rayleigh_polarized_sample_f64), and at every collision adds the
 * Stokes vector scattered towards a few view directions at the top
 * (sk_rayleigh_polarized_eval_f64, referred to the meridian plane),
 * attenuated on its way out. Prints I, Q, U and the degree of linear
 * polarisation beside Natraj, Li & Yung (2009, ApJ 691:1909), whose
 * corrected Coulson-Dave-Sekera tables use Q = I_r - I_l, the negative of
 * the meridian-plane Q computed here. Exits 0 when every value is within 5
 * standard errors of the table.
 *
 *   cc -std=c99 -O2 -I include c_examples/rayleigh_sky.c \
 *      -lm target/release/libscatterkit.a -lpthread -ldl -lm
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "scatterkit.h"

#define PHOTONS 100000
#define VIEWS 4

static uint64_t splitmix64(uint64_t *s) {
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/* A uniform in [0, 1) from the top 53 bits. */
static double uniform(uint64_t *s) { return (double)(splitmix64(s) >> 11) * 0x1p-53; }

int main(void) {
    const double pi = 3.14159265358979323846, tau = 0.5, mu0 = 0.2;
    /* Reflected at the top, mu = 0.52: azimuth (degrees) and the table's
     * I, Q, U (tau 0.5, albedo 0, mu0 0.2). */
    const double phi[VIEWS] = {0.0, 60.0, 90.0, 180.0};
    const double table[VIEWS][3] = {{0.13097041, 0.01968930, 0.00000000},
                                    {0.10280748, -0.04650218, 0.04917038},
                                    {0.09759154, -0.07273772, 0.02406753},
                                    {0.15600064, -0.00534093, 0.00000000}};
    const double mu = 0.52;
    sk_vec3_f64 view[VIEWS], ref[VIEWS];
    double sum[VIEWS][3] = {{0}}, sum2[VIEWS][3] = {{0}};
    sk_rayleigh_polarized_f64 air;
    uint64_t seed = 2009;
    int v, c, n, bad = 0;
    if (sk_rayleigh_polarized_new_f64(0.0, &air) != SK_OK) return 1;
    for (v = 0; v < VIEWS; v++) {
        double p = phi[v] * pi / 180.0, s = sqrt(1.0 - mu * mu);
        view[v] = (sk_vec3_f64){s * cos(p), s * sin(p), mu};
        ref[v] = sk_meridian_reference_f64(view[v], p);
    }
    for (n = 0; n < PHOTONS; n++) {
        sk_vec3_f64 k = {sqrt(1.0 - mu0 * mu0), 0.0, -mu0};
        sk_stokes_f64 s = {1.0, 0.0, 0.0, 0.0, sk_meridian_reference_f64(k, 0.0)};
        double acc[VIEWS][3] = {{0}}, depth = 0.0;
        for (;;) {
            sk_stokes_sample_f64 x;
            depth += log(1.0 - uniform(&seed)) * k.z; /* path -log(1 - u) along k; depth grows downwards */
            if (depth < 0.0 || depth > tau) break; /* out at the top, or absorbed below */
            for (v = 0; v < VIEWS; v++) {
                sk_stokes_f64 e;
                double att = exp(-depth / mu) / mu;
                if (sk_rayleigh_polarized_eval_f64(&air, k, &s, view[v], ref[v], &e) != SK_OK) return 1;
                acc[v][0] += e.i * att;
                acc[v][1] -= e.q * att; /* the tables' sign */
                acc[v][2] += e.u * att;
            }
            if (sk_rayleigh_polarized_sample_f64(&air, k, &s, uniform(&seed), uniform(&seed), &x) != SK_OK) return 1;
            k = x.dir;
            s = x.stokes;
        }
        for (v = 0; v < VIEWS; v++)
            for (c = 0; c < 3; c++) {
                sum[v][c] += acc[v][c];
                sum2[v][c] += acc[v][c] * acc[v][c];
            }
    }
    printf("tau 0.5, black ground, mu0 0.2; reflected at mu 0.52 (Monte Carlo | table)\n");
    printf("  phi        I                  Q                   U            degree of lin. pol.\n");
    for (v = 0; v < VIEWS; v++) {
        double m[3], z = 0.0, dop_mc, dop_tab;
        for (c = 0; c < 3; c++) {
            double mean = sum[v][c] / PHOTONS, var = (sum2[v][c] / PHOTONS - mean * mean) / PHOTONS;
            m[c] = pi * mu0 * mean;
            z = fmax(z, fabs(m[c] - table[v][c]) / (pi * mu0 * sqrt(var) + 1e-12));
        }
        dop_mc = sqrt(m[1] * m[1] + m[2] * m[2]) / m[0];
        dop_tab = sqrt(table[v][1] * table[v][1] + table[v][2] * table[v][2]) / table[v][0];
        printf("%5.0f  %.5f | %.5f  %+.5f | %+.5f  %+.5f | %+.5f  %.3f | %.3f  (max |z| %.1f)\n", phi[v], m[0],
               table[v][0], m[1], table[v][1], m[2], table[v][2], dop_mc, dop_tab, z);
        bad |= z > 5.0;
    }
    return bad;
}
