//! Constructors: `sk_phase_<model>` and its `_f64` twin for every model.

use super::*;

/// Isotropic scattering, p = 1/(4 pi).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_isotropic(out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Ok(Phase::isotropic())) }
}

/// Double twin of `sk_phase_new_isotropic`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_isotropic_f64(out: *mut sk_phase_f64) -> sk_status {
    unsafe { construct(out, Ok(Phase::isotropic())) }
}

/// Rayleigh scattering, p = 3/(16 pi) (1 + mu^2); sampled by exact inversion.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_rayleigh(out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Ok(Phase::rayleigh())) }
}

/// Double twin of `sk_phase_new_rayleigh`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_rayleigh_f64(out: *mut sk_phase_f64) -> sk_status {
    unsafe { construct(out, Ok(Phase::rayleigh())) }
}

/// Henyey-Greenstein with asymmetry -1 <= g <= 1 (g > 0 forward).
/// |g| = 1 is the Dirac limit transport codes pass for a background medium:
/// every sample is cos theta = g (the direction +-w_in), the density is +inf
/// at cos theta = g and 0 elsewhere, a sampled direction's density is +inf,
/// and the CDF is the step at g (skp_hg_new(+-1) of scatterkit_portable.h
/// gives the same). SK_ERR_DOMAIN for |g| > 1, NaN or inf; SK_ERR_NULL for a
/// NULL `out`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_hg(g: f32, out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Phase::henyey_greenstein(g)) }
}

/// Double twin of `sk_phase_new_hg`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_hg_f64(g: f64, out: *mut sk_phase_f64) -> sk_status {
    unsafe { construct(out, Phase::henyey_greenstein(g)) }
}

/// Rayleigh scattering with depolarisation factor 0 <= rho < 1 (air: about
/// 0.028); rho = 0 is plain Rayleigh. SK_ERR_DOMAIN outside [0, 1) or NaN.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_rayleigh_depolarized(
    depolarization: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::rayleigh_depolarized(depolarization)) }
}

/// Double twin of `sk_phase_new_rayleigh_depolarized`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_rayleigh_depolarized_f64(
    depolarization: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::rayleigh_depolarized(depolarization)) }
}

/// Draine's phase function (Jendersie & d'Eon 2023) with -1 < g < 1 and
/// finite alpha >= 0; alpha = 1 is Cornette-Shanks, alpha = 0 is HG. Sampled
/// exactly and accurately on the whole domain. SK_ERR_DOMAIN otherwise.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_draine(g: f32, alpha: f32, out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Phase::draine(g, alpha)) }
}

/// Double twin of `sk_phase_new_draine`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_draine_f64(
    g: f64,
    alpha: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::draine(g, alpha)) }
}

/// Cornette-Shanks (1992): Draine with alpha = 1; -1 < g < 1.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_cornette_shanks(g: f32, out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Phase::cornette_shanks(g)) }
}

/// Double twin of `sk_phase_new_cornette_shanks`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_cornette_shanks_f64(
    g: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::cornette_shanks(g)) }
}

/// The fog mixture (1 - w_d) HG(g_hg) + w_d Draine(g_d, alpha):
/// |g_hg| <= 1, |g_d| < 1, finite alpha >= 0, 0 <= w_d <= 1, else SK_ERR_DOMAIN.
/// |g_hg| = 1 is a Dirac lobe (sk_phase_new_hg): its weight sits at
/// cos theta = g_hg, where the density is +inf (a lobe of weight 0 adds
/// nothing), and the exact inverse returns g_hg for the uniforms it covers.
/// sk_phase_sample_cos inverts the mixture's CDF exactly (monotone);
/// sk_phase_sample_cos_by_lobe is the paper's cheaper lobe-choice sampler.
/// Construction tabulates seeds for the inverse (about 10 microseconds):
/// build once per medium.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_fog(
    g_hg: f32,
    g_d: f32,
    alpha: f32,
    w_d: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::fog(g_hg, g_d, alpha, w_d)) }
}

/// Double twin of `sk_phase_new_fog`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_fog_f64(
    g_hg: f64,
    g_d: f64,
    alpha: f64,
    w_d: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::fog(g_hg, g_d, alpha, w_d)) }
}

/// Fournier-Forand (1994) for ocean particles of relative refractive index
/// 1 < n <= 1.8 with a Junge size distribution of slope 3 < mu_j < 5, else
/// SK_ERR_DOMAIN. The CDF is rearranged so that it neither cancels nor
/// divides 0/0 (the published form does at delta = 1); sk_phase_sample_cos
/// solves it by bracketed Newton steps in double, within 1.1e-15 (double)
/// and 3e-8 (float) of 50-digit references.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_fournier_forand(
    n: f32,
    mu_j: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::fournier_forand(n, mu_j)) }
}

/// Double twin of `sk_phase_new_fournier_forand`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_fournier_forand_f64(
    n: f64,
    mu_j: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::fournier_forand(n, mu_j)) }
}

/// Fournier-Forand from the backscatter fraction FLT_MIN <= b < 1/2
/// (DBL_MIN for the double twin: a smaller b would give a subnormal nu,
/// with too few bits to give b back) and 1 < n <= 1.8, as oceanographers
/// specify it (nu = -ln(2 b (d90 - 1) + 1) / ln d90, d90 = 2 / (3 (n -
/// 1)^2), rounded to the precision and kept inside (-1, 0)); SK_ERR_DOMAIN
/// outside the ranges.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_fournier_forand_backscatter(
    b: f32,
    n: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::fournier_forand_backscatter(b, n)) }
}

/// Double twin of `sk_phase_new_fournier_forand_backscatter`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_fournier_forand_backscatter_f64(
    b: f64,
    n: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::fournier_forand_backscatter(b, n)) }
}

/// The Gegenbauer kernel of Reynolds & McCormick (1980), p proportional to
/// (1 + g^2 - 2 g mu)^-(alpha + 1): -1/2 < alpha <= 1000, |g| < 1, else
/// SK_ERR_DOMAIN; alpha = 1/2 is HG (g is then the mean cosine, otherwise
/// not). Its inverse CDF is closed form, written without cancellation:
/// within 5e-15 (double) and 3e-8 (float) of 50-digit references.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_gegenbauer(
    alpha: f32,
    g: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::gegenbauer(alpha, g)) }
}

/// Double twin of `sk_phase_new_gegenbauer`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_gegenbauer_f64(
    alpha: f64,
    g: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::gegenbauer(alpha, g)) }
}

/// Two-lobe Henyey-Greenstein, w HG(g1) + (1 - w) HG(g2): |g1| < 1,
/// |g2| < 1, 0 <= w <= 1, else SK_ERR_DOMAIN. The fog mixture with alpha =
/// 0 (each |g| <= 1; |g| = 1 a Dirac lobe as in sk_phase_new_fog;
/// sk_phase_get_params reports SK_PHASE_FOG with g_hg = g2, g_d = g1,
/// alpha = 0, w_d = w): sk_phase_sample_cos inverts the mixture's CDF
/// exactly (monotone), sk_phase_sample_cos_by_lobe picks a lobe with the
/// uniform and reuses it (cheaper, not monotone). Construction takes about
/// 10 microseconds: build once per medium.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_two_lobe_hg(
    g1: f32,
    g2: f32,
    w: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::two_lobe_hg(g1, g2, w)) }
}

/// Double twin of `sk_phase_new_two_lobe_hg`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_two_lobe_hg_f64(
    g1: f64,
    g2: f64,
    w: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::two_lobe_hg(g1, g2, w)) }
}

/// The modified Henyey-Greenstein function of Bevilacqua & Depeursinge
/// (JOSA A 16(12), 1999), beta HG(g_HG) + (1 - beta) (3/(4 pi)) cos^2,
/// set by its mean cosine g and gamma = (1 - chi_2)/(1 - chi_1): g_HG is
/// the positive root of g x^2 + (gamma (1 - g) - 3/5) x - 2g/5 = 0 and
/// beta = g/g_HG. The cos^2 lobe is the Draine function with g = 0 and
/// alpha = 2^70 (within 1e-21 of it), so the value is a fog mixture
/// (sk_phase_get_params: g_hg = g_HG, g_d = 0, alpha = 2^70,
/// w_d = 1 - beta). SK_ERR_DOMAIN unless 0 < g < 1 and
/// 0.6 < gamma <= 1 + g (gamma = 1 + g is HG itself; taken with 4 DBL_EPSILON
/// of relative slack, for a gamma rounded up from 1 + g).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_modified_hg(
    g: f32,
    gamma: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::modified_hg(g, gamma)) }
}

/// Double twin of `sk_phase_new_modified_hg`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_modified_hg_f64(
    g: f64,
    gamma: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::modified_hg(g, gamma)) }
}

/// The modified Henyey-Greenstein function of sk_phase_new_modified_hg set by
/// g and delta = (1 - chi_3)/(1 - chi_1): g_HG = sqrt((1 - delta (1 - g))/g),
/// beta = g/g_HG. SK_ERR_DOMAIN unless 0 < g < 1 and
/// 1 < delta <= 1 + g + g^2 (the top is HG itself; taken with 4 DBL_EPSILON
/// of relative slack).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_modified_hg_delta(
    g: f32,
    delta: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::modified_hg_delta(g, delta)) }
}

/// Double twin of `sk_phase_new_modified_hg_delta`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_modified_hg_delta_f64(
    g: f64,
    delta: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::modified_hg_delta(g, delta)) }
}

/// The two-lobe HG whose second lobe is isotropic,
/// (1 - beta) HG(g_HG) + beta/(4 pi) (Prahl's "modified HG", 1988), set by
/// g and gamma = (1 - chi_2)/(1 - chi_1): g_HG = (1 - gamma (1 - g))/g,
/// beta = 1 - g/g_HG; built as sk_phase_new_two_lobe_hg(g_HG, 0, 1 - beta).
/// SK_ERR_DOMAIN unless 0 < g < 1 and 1 < gamma <= 1 + g (the top, HG, taken
/// with 4 DBL_EPSILON of relative slack).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_two_lobe_hg_gamma(
    g: f32,
    gamma: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::two_lobe_hg_gamma(g, gamma)) }
}

/// Double twin of `sk_phase_new_two_lobe_hg_gamma`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_two_lobe_hg_gamma_f64(
    g: f64,
    gamma: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::two_lobe_hg_gamma(g, gamma)) }
}

/// The two-lobe HG of sk_phase_new_two_lobe_hg_gamma set by g and
/// delta = (1 - chi_3)/(1 - chi_1): g_HG = sqrt((1 - delta (1 - g))/g).
/// SK_ERR_DOMAIN unless 0 < g < 1 and 1 < delta <= 1 + g + g^2 (the top, HG,
/// taken with 4 DBL_EPSILON of relative slack).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_two_lobe_hg_delta(
    g: f32,
    delta: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::two_lobe_hg_delta(g, delta)) }
}

/// Double twin of `sk_phase_new_two_lobe_hg_delta`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_two_lobe_hg_delta_f64(
    g: f64,
    delta: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::two_lobe_hg_delta(g, delta)) }
}

/// The Gegenbauer kernel (sk_phase_new_gegenbauer) with mean cosine
/// 0 < g < 1 and gamma = (1 - chi_2)/(1 - chi_1), found by root-finding
/// on the kernel's moments in closed form (about 0.3 ms: build once). It
/// reaches gamma in a band around HG's 1 + g, above it too (flatter than
/// HG), e.g. 1.334 < gamma < 1.874 at g = 0.6; elsewhere SK_ERR_DOMAIN.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_gegenbauer_gamma(
    g: f32,
    gamma: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::gegenbauer_gamma(g, gamma)) }
}

/// Double twin of `sk_phase_new_gegenbauer_gamma`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_gegenbauer_gamma_f64(
    g: f64,
    gamma: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::gegenbauer_gamma(g, gamma)) }
}

/// The Gegenbauer kernel with mean cosine 0 < g < 1 and
/// delta = (1 - chi_3)/(1 - chi_1), as sk_phase_new_gegenbauer_gamma (e.g.
/// 1.513 < delta < 2.302 at g = 0.6); elsewhere SK_ERR_DOMAIN.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_gegenbauer_delta(
    g: f32,
    delta: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::gegenbauer_delta(g, delta)) }
}

/// Double twin of `sk_phase_new_gegenbauer_delta`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_gegenbauer_delta_f64(
    g: f64,
    delta: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::gegenbauer_delta(g, delta)) }
}

/// The fog phase function fitted to Mie scattering by water droplets of
/// diameter 0 < d <= 50 micrometres (Jendersie & d'Eon 2023; four ranges
/// split at 0.1, 1.5 and 5 um). SK_ERR_DOMAIN outside (0, 50] or NaN.
/// Construction takes about 10 microseconds (see sk_phase_new_fog).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_fog_diameter(
    diameter_um: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::fog_diameter(diameter_um)) }
}

/// Double twin of `sk_phase_new_fog_diameter`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_fog_diameter_f64(
    diameter_um: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::fog_diameter(diameter_um)) }
}

/// The cheapest of isotropic, HG, Rayleigh, Draine and the full fog fit
/// (by measured sampling cost) whose density stays within total-variation
/// distance `tolerance` (0 < tolerance < 1) of the fog fit for droplets of
/// 0 < diameter_um <= 50 micrometres; HG and Draine get best-fit parameters.
/// Takes milliseconds: build once per medium. SK_ERR_DOMAIN outside the ranges.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_particle(
    diameter_um: f32,
    tolerance: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::particle(diameter_um, tolerance)) }
}

/// Double twin of `sk_phase_new_particle`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_particle_f64(
    diameter_um: f64,
    tolerance: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::particle(diameter_um, tolerance)) }
}
