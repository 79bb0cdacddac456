/* |g| = 1, the Dirac limit transport codes pass, through the C ABI (float
 * and double) and the portable header, side by side: every sample finite
 * and at the limit (cos theta = g, the direction +-w_in), the density +inf
 * at cos theta = g and 0 elsewhere, the same values from both; the HG lobes
 * of a two-lobe HG and of the fog the same; the portable batches too. */
#include <math.h>
#include <string.h>

#include "scatterkit.h"
#include "scatterkit_portable.h"
#include "check.h"

static const float US[] = {0.0f, 1e-30f, 0.25f, 0.5f, 0.75f, 1.0f, -3.0f, 4.0f};
#define NU (sizeof US / sizeof US[0])

static int near(float a, float b) { return fabsf(a - b) <= 1e-6f; }

static void hg(float g) {
    sk_phase p;
    sk_phase_f64 p64;
    skp_hg h;
    sk_vec3 w = {0.48f, 0.6f, 0.64f};
    skp_vec3 wp = {0.48f, 0.6f, 0.64f};
    size_t i;
    CHECK(sk_phase_new_hg(g, &p) == SK_OK);
    CHECK(sk_phase_new_hg_f64(g, &p64) == SK_OK);
    CHECK(skp_hg_new(g, &h) == 1);
    for (i = 0; i < NU; i++) {
        float u = US[i], pdf = 0.0f;
        double pdf64 = 0.0;
        sk_vec3 d = sk_phase_sample_dir(&p, w, u, 0.3f, &pdf);
        sk_vec3_f64 w64 = {0.48, 0.6, 0.64};
        sk_vec3_f64 d64 = sk_phase_sample_dir_f64(&p64, w64, u, 0.3, &pdf64);
        skp_dir_sample r = skp_hg_sample_dir(h, wp, u, 0.3f);
        CHECK(sk_phase_sample_cos(&p, u) == g);
        CHECK(sk_phase_sample_cos_f64(&p64, u) == g);
        CHECK(skp_hg_sample_cos(h, u) == g);
        CHECK(r.cos_theta == g && isinf(r.pdf) && isinf(pdf) && isinf(pdf64));
        CHECK(near(d.x, g * w.x) && near(d.y, g * w.y) && near(d.z, g * w.z));
        CHECK(near(r.dir.x, g * w.x) && near(r.dir.y, g * w.y) && near(r.dir.z, g * w.z));
        CHECK(fabs(d64.x - g * w64.x) < 1e-12 && fabs(d64.z - g * w64.z) < 1e-12);
    }
    CHECK(isnan(sk_phase_sample_cos(&p, NAN)) && isnan(skp_hg_sample_cos(h, NAN)));
    CHECK(isinf(sk_phase_pdf(&p, g)) && isinf(skp_hg_pdf(h, g)) && isinf(sk_phase_pdf_f64(&p64, g)));
    CHECK(sk_phase_pdf(&p, 0.3f) == 0.0f && skp_hg_pdf(h, 0.3f) == 0.0f);
    CHECK(sk_phase_pdf(&p, -g) == 0.0f && skp_hg_pdf(h, -g) == 0.0f);
    CHECK(sk_phase_cdf(&p, 1.0f) == 1.0f && sk_phase_cdf(&p, 0.0f) == (g > 0.0f ? 0.0f : 1.0f));
    /* The portable batches, from an sk_phase at the limit. */
    {
        float u[NU], ox[NU], oy[NU], oz[NU], pdf[NU], cosv[NU], wx[NU], wy[NU], wz[NU];
        for (i = 0; i < NU; i++) {
            u[i] = US[i] < 0.0f ? 0.0f : (US[i] > 1.0f ? 1.0f : US[i]);
            wx[i] = w.x;
            wy[i] = w.y;
            wz[i] = w.z;
        }
        CHECK(sk_phase_sample_cos_n_portable(&p, u, cosv, NU) == SK_OK);
        CHECK(sk_phase_sample_dir_n_portable(&p, wx, wy, wz, u, u, ox, oy, oz, pdf, NU) == SK_OK);
        for (i = 0; i < NU; i++) {
            CHECK(cosv[i] == g && isinf(pdf[i]) && near(oz[i], g * w.z));
        }
    }
}

static void mixtures(float g) {
    sk_phase two, fog;
    skp_two_lobe tl;
    skp_fog fp;
    skp_vec3 wp = {0.0f, 0.0f, 1.0f};
    /* Two-lobe HG: the first lobe, weight 0.25, is the Dirac lobe. */
    CHECK(sk_phase_new_two_lobe_hg(g, -0.3f, 0.25f, &two) == SK_OK);
    CHECK(skp_two_lobe_new(g, -0.3f, 0.25f, &tl) == 1);
    CHECK(isinf(sk_phase_pdf(&two, g)) && isinf(skp_two_lobe_pdf(tl, g)));
    CHECK(near(sk_phase_pdf(&two, 0.1f), skp_two_lobe_pdf(tl, 0.1f)));
    /* The lobe choice picks the Dirac lobe for u < w in both. */
    CHECK(sk_phase_sample_cos_by_lobe(&two, 0.1f) == g && skp_two_lobe_sample_cos(tl, 0.1f) == g);
    /* The exact inverse puts the lobe's weight at its pole. */
    CHECK(sk_phase_sample_cos(&two, g > 0.0f ? 0.9f : 0.1f) == g);
    /* The fog with a Dirac HG lobe; with w_d = 1 it adds nothing. */
    CHECK(sk_phase_new_fog(g, 0.6f, 20.0f, 0.4f, &fog) == SK_OK);
    CHECK(skp_fog_new(g, 0.6f, 20.0f, 0.4f, &fp) == 1);
    CHECK(isinf(sk_phase_pdf(&fog, g)) && isinf(skp_fog_pdf(fp, g)));
    CHECK(sk_phase_sample_cos_by_lobe(&fog, 0.7f) == g && skp_fog_sample_cos(fp, 0.7f) == g);
    CHECK(skp_fog_sample_dir(fp, wp, 0.7f, 0.2f).dir.z == g);
    CHECK(sk_phase_new_fog(g, 0.6f, 20.0f, 1.0f, &fog) == SK_OK);
    CHECK(skp_fog_new(g, 0.6f, 20.0f, 1.0f, &fp) == 1);
    CHECK(isfinite(sk_phase_pdf(&fog, g)) && isfinite(skp_fog_pdf(fp, g)));
    CHECK(near(sk_phase_pdf(&fog, g) / skp_fog_pdf(fp, g), 1.0f));
    /* Past the limit: refused by both. */
    CHECK(sk_phase_new_hg(1.0000001f * g, &two) == SK_ERR_DOMAIN);
    CHECK(skp_two_lobe_new(1.0000001f * g, 0.0f, 0.5f, &tl) == 0 && isnan(tl.w));
}

int main(void) {
    hg(1.0f);
    hg(-1.0f);
    mixtures(1.0f);
    mixtures(-1.0f);
    printf("dirac: %d checks passed, %d failed\n", passed, failed);
    return failed;
}
