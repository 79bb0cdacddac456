/* A whole photon loop, the library's system-level figure: a slab of optical
 * depth 2 (z in [0, 1]), albedo 0.9 as a weight, HG g = 0.75, matched
 * boundaries, photons entering at z = 0 along +z, written twice:
 *   lib.*    through the C ABI, one call per flight: sk_free_path_f64 in
 *            the homogeneous slab (the call a homogeneous code makes, one
 *            draw per flight as MCML's), sk_delta_track_f64 in the
 *            heterogeneous ones (the arguments filled once per medium, the
 *            ray per flight), and sk_phase_sample_dir_f64 for the new
 *            direction; lib.homdt is the homogeneous slab through
 *            sk_delta_track_f64 at its own majorant (two draws per flight);
 *   inline.* the peers' formulas inline (the medium read at run time): MCML's free path -ln(xi)/mu_t and
 *            its HG inverse and direction update (Wang, Jacques & Zheng
 *            1995), and for the heterogeneous media pbrt-v4's delta
 *            tracking (exponential steps at the majorant, a collision kept
 *            with probability sigma_t/sigma_maj).
 * The inline loop reads sigma_t, the majorant and g from a struct filled at
 * run time, as MCML reads its layer records and pbrt-v4 its medium: compiled
 * in as constants, they were folded (1 - g^2, 1/2g, a division by 2 turned
 * into a product), which no code reading its input gets.
 * inline.cbfn is the inline loop reading the callback medium through a
 * function pointer it cannot see into (the library's callback, het, as a
 * code keeps a medium its user supplies): what the callback itself costs,
 * whoever calls it.
 * Media: hom (sigma_t = 2), cb (a callback, sigma_t(z) = 1 + 2z, majorant
 * 3) and grid (the same density on a 1 x 1 x 64 node grid, linear in z:
 * exact). The three have the same optical depth, albedo and g, so one
 * adding-doubling answer serves them all.
 * Prints per mode "name<TAB>ns per photon<TAB>0", then "name.R" and
 * "name.T" lines with the reflected and transmitted weight per photon and
 * its standard error. argv[1]: photons (default 10^6); argv[2]: rounds
 * (default 5), each running every mode once in turn, the time printed the
 * median over rounds (one run of each mode moved by up to 8 % from run to
 * run on a shared machine; in rounds, a drift reaches the library's and
 * the inline loop's times alike). Every round starts from the same seed,
 * so R and T are the same in each. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scatterkit.h"
#include "slab.h"

#define ALBEDO 0.9
#define G 0.75
#define NZ 64

enum medium { HOM, HOMDT, CB, GRID };
static double sigma_t(enum medium m, double z) { return m == CB ? 1.0 + 2.0 * z : 2.0; }
static sk_coefficients_f64 het(void *ctx, sk_vec3_f64 p) {
    sk_coefficients_f64 c;
    (void)ctx;
    c.sigma_a = 0.0, c.sigma_s = 1.0 + 2.0 * p.z;
    return c;
}
static sk_coefficients_f64 hom(void *ctx, sk_vec3_f64 p) {
    sk_coefficients_f64 c = {0.0, 2.0};
    (void)ctx, (void)p;
    return c;
}

static double density[NZ];

/* sigma_t of the grid medium: the node values interpolated linearly in z,
   as a code reading its own 1-D grid would. */
static double grid_sigma(double z) {
    double x = z * (NZ - 1);
    int i = x <= 0.0 ? 0 : (x >= NZ - 1 ? NZ - 2 : (int)x);
    double f = x - i;
    return density[i] + f * (density[i + 1] - density[i]);
}

/* The medium as the inline loop reads it: filled at run time from
   `input`, as a code fills its records from its input file. */
typedef struct {
    double sigma_t, sigma_maj, g;
} layer;
static volatile double input[3] = {2.0, 3.0, G};
static sk_medium_fn_f64 volatile supplied = het;

/* The inline flight: MCML's step in the homogeneous slab, pbrt-v4's delta
   tracking at the majorant in the heterogeneous ones. */
static double inline_flight(enum medium m, const layer *l, const double o[3], const double d[3], double tb,
                            xo *x) {
    double t = 0.0;
    if (m == HOM || m == HOMDT) return -log(1.0 - xo_u(x)) / l->sigma_t;
    for (;;) {
        t += -log(1.0 - xo_u(x)) / l->sigma_maj;
        if (t >= tb) return t;
        if (xo_u(x) * l->sigma_maj < (m == GRID ? grid_sigma(o[2] + t * d[2]) : sigma_t(m, o[2] + t * d[2])))
            return t;
    }
}

/* pbrt-v4's delta tracking with the medium behind a pointer the code was
   given (loaded once per flight, as from the code's own records). */
static double inline_flight_fn(const layer *l, const double o[3], const double d[3], double tb, xo *x) {
    sk_medium_fn_f64 medium = supplied;
    double t = 0.0;
    for (;;) {
        sk_vec3_f64 p;
        sk_coefficients_f64 c;
        t += -log(1.0 - xo_u(x)) / l->sigma_maj;
        if (t >= tb) return t;
        p.x = o[0] + t * d[0], p.y = o[1] + t * d[1], p.z = o[2] + t * d[2];
        c = medium(NULL, p);
        if (xo_u(x) * l->sigma_maj < c.sigma_a + c.sigma_s) return t;
    }
}

typedef struct {
    double sum, sum2;
} tally;
static void add(tally *t, double w) { t->sum += w, t->sum2 += w * w; }
static double se(const tally *t, long n) {
    double m = t->sum / n;
    return sqrt((t->sum2 / n - m * m) / n);
}

static sk_grid_f64 grid;
static sk_phase_f64 hg;

/* The loop, written once; inlined into the wrappers below with `lib` a
   constant (1 the library, 0 inline, 2 inline with the callback medium
   behind its pointer), so each kind is compiled on its own (sharing one body, the
   two modes' registers and layout moved each other's times by up to 8 %). */
#if defined(__GNUC__)
#define ALWAYS_INLINE static inline __attribute__((always_inline))
#define NOINLINE static __attribute__((noinline))
#else
#define ALWAYS_INLINE static inline
#define NOINLINE static
#endif

/* What one mode gave: ns per photon, and R and T with their standard
   errors. */
typedef struct {
    double ns, r, r_se, t, t_se;
} result;

ALWAYS_INLINE result run(enum medium m, int lib, long photons) {
    static xo state;
    static sk_rng rng;
    sk_track_args_f64 a;
    layer l;
    tally r_w = {0, 0}, t_w = {0, 0};
    long i;
    double t0;
    l.sigma_t = input[0], l.sigma_maj = input[1], l.g = input[2];
    state = xo_seed(42);
    rng.state = &state, rng.next_u64 = xo_next;
    memset(&a, 0, sizeof a);
    if (m == GRID) {
        a.medium.grid = &grid;
    } else {
        a.medium.coefficients = m == CB ? het : hom;
        a.medium.sigma_maj = m == CB ? 3.0 : 2.0;
    }
    a.rng = &rng;
    t0 = now_s();
    for (i = 0; i < photons; i++) {
        double o[3] = {0.0, 0.0, 0.0}, d[3] = {0.0, 0.0, 1.0}, w = 1.0;
        for (;;) {
            double tb = to_boundary(o[2], d[2]), t;
            if (lib == 1 && m == HOM) {
                t = sk_free_path_f64(l.sigma_t, xo_u(&state));
            } else if (lib == 1) {
                sk_track_result_f64 res;
                a.o.x = o[0], a.o.y = o[1], a.o.z = o[2];
                a.d.x = d[0], a.d.y = d[1], a.d.z = d[2];
                a.t_max = tb;
                if (sk_delta_track_f64(&a, &res) != SK_OK) exit(3);
                t = res.event == SK_TRACK_ESCAPED ? tb : res.t;
            } else if (lib == 2) {
                t = inline_flight_fn(&l, o, d, tb, &state);
            } else {
                t = inline_flight(m, &l, o, d, tb, &state);
            }
            if (t >= tb) {
                if (d[2] > 0.0) add(&t_w, w);
                else add(&r_w, w);
                break;
            }
            o[0] += t * d[0], o[1] += t * d[1], o[2] += t * d[2];
            w *= ALBEDO;
            if (w < 1e-4) {
                if (xo_u(&state) < 0.1) w *= 10.0;
                else break;
            }
            if (lib == 1) {
                sk_vec3_f64 win = {d[0], d[1], d[2]}, out;
                out = sk_phase_sample_dir_f64(&hg, win, xo_u(&state), xo_u(&state), NULL);
                d[0] = out.x, d[1] = out.y, d[2] = out.z;
            } else {
                mcml_scatter(d, l.g, &state);
            }
        }
    }
    t0 = now_s() - t0;
    {
        result x;
        x.ns = 1e9 * t0 / photons;
        x.r = r_w.sum / photons, x.r_se = se(&r_w, photons);
        x.t = t_w.sum / photons, x.t_se = se(&t_w, photons);
        return x;
    }
}

NOINLINE result run_lib(enum medium m, long photons) { return run(m, 1, photons); }
NOINLINE result run_inline(enum medium m, long photons) { return run(m, 0, photons); }
NOINLINE result run_inline_fn(long photons) { return run(CB, 2, photons); }

/* The modes, in the order each round runs them. */
#define MODES 8
static const char *const names[MODES] = {"inline.hom",  "lib.hom", "lib.homdt",   "inline.cb",
                                         "inline.cbfn", "lib.cb",  "inline.grid", "lib.grid"};
static result mode(int k, long photons) {
    switch (k) {
    case 0: return run_inline(HOM, photons);
    case 1: return run_lib(HOM, photons);
    case 2: return run_lib(HOMDT, photons);
    case 3: return run_inline(CB, photons);
    case 4: return run_inline_fn(photons);
    case 5: return run_lib(CB, photons);
    case 6: return run_inline(GRID, photons);
    default: return run_lib(GRID, photons);
    }
}

static int by_value(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

#define MAX_ROUNDS 99

int main(int argc, char **argv) {
    long photons = argc > 1 ? atol(argv[1]) : 1000000;
    int rounds = argc > 2 ? atoi(argv[2]) : 5, k, i;
    static double ns[MODES][MAX_ROUNDS];
    result last[MODES];
    if (photons <= 0 || rounds < 1 || rounds > MAX_ROUNDS) return 2;
    for (k = 0; k < NZ; k++) density[k] = 1.0 + 2.0 * k / (NZ - 1.0);
    if (sk_grid_new_f64(density, 1, 1, NZ, 0.0, 1.0, &grid) != SK_OK) return 4;
    {
        sk_vec3_f64 lo = {-1e6, -1e6, 0.0}, hi = {1e6, 1e6, 1.0};
        if (sk_grid_set_box_f64(&grid, lo, hi) != SK_OK) return 4;
    }
    if (sk_phase_new_hg_f64(G, &hg) != SK_OK) return 4;
    for (i = 0; i < rounds; i++) {
        for (k = 0; k < MODES; k++) {
            last[k] = mode(k, photons);
            ns[k][i] = last[k].ns;
        }
    }
    for (k = 0; k < MODES; k++) {
        double *x = ns[k];
        int h = rounds / 2;
        qsort(x, (size_t)rounds, sizeof(double), by_value);
        printf("%s\t%.1f\t0\n", names[k], rounds % 2 ? x[h] : 0.5 * (x[h - 1] + x[h]));
        printf("%s.R\t%.6f\t%.6f\n", names[k], last[k].r, last[k].r_se);
        printf("%s.T\t%.6f\t%.6f\n", names[k], last[k].t, last[k].t_se);
    }
    return 0;
}
