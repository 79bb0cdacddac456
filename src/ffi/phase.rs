//! Phase functions.
//!
//! `sk_phase` holds a [`Phase<f32>`] (`sk_phase_f64` a `Phase<f64>`) in
//! private storage. Every call checks the stored tag before it reads the
//! value, so a NULL, zeroed or never-constructed phase gives NaN or an error
//! rather than undefined behaviour.

use super::{
    CVec, SOA_BLOCK, check_soa, map_arrays, sk_status, sk_vec3, sk_vec3_f64, soa_blocks,
    write_result,
};
use crate::error::Error;
use crate::math::real::Real;
use crate::phase::{Phase, PhaseFunction, PhaseVisitor, check_uniforms};

/// A phase function (float). A plain value with no pointers inside: build it
/// with an `sk_phase_*` constructor, then copy it and share it freely across
/// threads. Its contents are private, and some of its bytes are padding a
/// constructor need not define: compare phases with sk_phase_get_params,
/// not memcmp.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_phase {
    /// Private storage; do not read or write.
    pub opaque: [u32; 32],
}

/// A phase function (double); see `sk_phase`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_phase_f64 {
    /// Private storage; do not read or write.
    pub opaque: [u64; 32],
}

/// Storage of a [`Phase<T>`] behind a C type.
pub(crate) trait PhaseStore: Copy {
    /// The float type of the phase stored.
    type T: Real;
    /// The C type `sk_phase_get_params` writes for it.
    type Params;
    const ZEROED: Self;
    fn params(model: u32, count: u32, params: [Self::T; 4]) -> Self::Params;
}
impl PhaseStore for sk_phase {
    type T = f32;
    type Params = sk_phase_params;
    const ZEROED: Self = sk_phase { opaque: [0; 32] };
    fn params(model: u32, count: u32, params: [f32; 4]) -> sk_phase_params {
        sk_phase_params {
            model,
            count,
            params,
        }
    }
}
impl PhaseStore for sk_phase_f64 {
    type T = f64;
    type Params = sk_phase_params_f64;
    const ZEROED: Self = sk_phase_f64 { opaque: [0; 32] };
    fn params(model: u32, count: u32, params: [f64; 4]) -> sk_phase_params_f64 {
        sk_phase_params_f64 {
            model,
            count,
            params,
        }
    }
}

const _: () = {
    use core::mem::{align_of, size_of};
    assert!(size_of::<Phase<f32>>() <= size_of::<sk_phase>());
    assert!(align_of::<Phase<f32>>() <= align_of::<sk_phase>());
    assert!(size_of::<Phase<f64>>() <= size_of::<sk_phase_f64>());
    assert!(align_of::<Phase<f64>>() <= align_of::<sk_phase_f64>());
};

/// Packs a phase into zeroed storage. The enum's padding (after the tag,
/// and past a shorter variant) need not be written: compare two phases by
/// their parameters (sk_phase_get_params), not by their bytes.
fn store<S: PhaseStore>(phase: Phase<S::T>) -> S {
    let mut s = S::ZEROED;
    // SAFETY: size and alignment checked above; S is plain bytes.
    unsafe { (&mut s as *mut S).cast::<Phase<S::T>>().write(phase) };
    s
}

/// The phase behind `p`, or `None` if `p` is NULL or its tag is not one
/// `store` writes.
#[inline(always)]
pub(crate) unsafe fn load<'a, S: PhaseStore>(p: *const S) -> Option<&'a Phase<S::T>> {
    if p.is_null() {
        return None;
    }
    // SAFETY: p points to an S (module contract), which begins with the u32
    // tag of the repr(C, u32) enum; the payload is floats, valid for any bits.
    let tag = unsafe { p.cast::<u32>().read() };
    if tag == 0 || tag > LAST_TAG {
        return None;
    }
    Some(unsafe { &*p.cast::<Phase<S::T>>() })
}

/// The discriminant of `Phase`'s last variant: valid tags are
/// `1..=LAST_TAG` (`Phase` is `#[repr(C, u32)]` with tags from 1).
const LAST_TAG: u32 = 8;

/// The tag of each variant, matched exhaustively: a new model fails to
/// compile here until its tag is listed and `LAST_TAG` follows.
#[cfg(test)]
fn tag_of<T: Real>(p: &Phase<T>) -> u32 {
    match p {
        Phase::Isotropic(_) => 1,
        Phase::Rayleigh(_) => 2,
        Phase::RayleighDepolarized(_) => 3,
        Phase::HenyeyGreenstein(_) => 4,
        Phase::Draine(_) => 5,
        Phase::Fog(_) => 6,
        Phase::Gegenbauer(_) => 7,
        Phase::FournierForand(_) => 8,
    }
}

unsafe fn construct<S: PhaseStore>(out: *mut S, r: Result<Phase<S::T>, Error>) -> sk_status {
    unsafe { write_result(out, r.map(store)) }
}

unsafe fn pdf<S: PhaseStore>(p: *const S, cos_theta: S::T) -> S::T {
    unsafe { load(p) }.map_or(S::T::NAN, |ph| ph.pdf(cos_theta))
}

unsafe fn cdf<S: PhaseStore>(p: *const S, cos_theta: S::T) -> S::T {
    unsafe { load(p) }.map_or(S::T::NAN, |ph| ph.cdf(cos_theta))
}

unsafe fn mean_cosine<S: PhaseStore>(p: *const S) -> S::T {
    unsafe { load(p) }.map_or(S::T::NAN, |ph| ph.mean_cosine())
}

// The scalar entry points check the pointer and the tag, then jump to one
// function per model (`#[inline(never)]`): the entry stays a check and a
// jump, and each model's code saves only the registers it needs, instead of
// every call paying the prologue of the largest model.

#[inline(never)]
fn cos_of<T: Real, M: PhaseFunction<T>>(m: &M, u: T) -> T {
    m.sample_cos(u)
}

/// [`cos_of`] on the model inside a `Phase`.
struct CosOf<T>(T);

impl<T: Real> PhaseVisitor<T> for CosOf<T> {
    type Output = T;
    #[inline(always)]
    fn visit<M: PhaseFunction<T>>(self, m: &M) -> T {
        cos_of(m, self.0)
    }
}

unsafe fn sample_cos<S: PhaseStore>(p: *const S, u: S::T) -> S::T {
    match unsafe { load(p) } {
        Some(ph) => ph.visit(CosOf(u)),
        None => S::T::NAN,
    }
}

/// One model's direction; writes the density through a non-NULL `pdf_out`.
/// With the C calling convention of the entry points (the vector in
/// registers both ways), so that the entry ends in a jump here: with Rust's,
/// it called this, the vector went through the stack both ways, and the
/// result's three 4-byte stores were read back as one 8-byte load, which
/// store forwarding cannot serve.
#[inline(never)]
unsafe extern "C" fn dir_of<T: Real, M: PhaseFunction<T>, V: CVec<T = T>>(
    m: &M,
    w_in: V,
    u1: T,
    u2: T,
    pdf_out: *mut T,
) -> V {
    let (dir, pdf) = m.sample_dir(w_in.to_vec(), u1, u2);
    // SAFETY: a non-NULL pdf_out is writable (module contract).
    if let Some(out) = unsafe { pdf_out.as_mut() } {
        *out = pdf;
    }
    V::from_vec(dir)
}

/// [`dir_of`] on the model inside a `Phase`, with a `pdf_out` the caller
/// vouches for (NULL or writable).
struct DirOf<T, V> {
    w_in: V,
    u1: T,
    u2: T,
    pdf_out: *mut T,
}

impl<T: Real, V: CVec<T = T>> PhaseVisitor<T> for DirOf<T, V> {
    type Output = V;
    #[inline(always)]
    fn visit<M: PhaseFunction<T>>(self, m: &M) -> V {
        // SAFETY: pdf_out is NULL or writable (the entry points' contract).
        unsafe { dir_of(m, self.w_in, self.u1, self.u2, self.pdf_out) }
    }
}

unsafe fn sample_dir<S: PhaseStore, V: CVec<T = S::T>>(
    p: *const S,
    w_in: V,
    u1: S::T,
    u2: S::T,
    pdf_out: *mut S::T,
) -> V {
    match unsafe { load(p) } {
        Some(ph) => ph.visit(DirOf {
            w_in,
            u1,
            u2,
            pdf_out,
        }),
        None => {
            let nan = S::T::NAN;
            // SAFETY: as in dir_of.
            if let Some(out) = unsafe { pdf_out.as_mut() } {
                *out = nan;
            }
            V::from_vec(crate::Vec3::new(nan, nan, nan))
        }
    }
}

unsafe fn sample_cos_n<S: PhaseStore>(
    p: *const S,
    u: *const S::T,
    cos_out: *mut S::T,
    n: usize,
) -> sk_status {
    if p.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(ph) = (unsafe { load(p) }) else {
        return sk_status::SK_ERR_DOMAIN;
    };
    unsafe {
        map_arrays(u, cos_out, n, check_uniforms, |u, out| {
            ph.sample_cos_each_in_range(u, out);
            Ok(())
        })
    }
}

#[allow(clippy::too_many_arguments)]
unsafe fn sample_dir_n<S: PhaseStore>(
    p: *const S,
    w: [*const S::T; 3],
    u1: *const S::T,
    u2: *const S::T,
    out: [*mut S::T; 3],
    pdf_out: *mut S::T,
    n: usize,
) -> sk_status {
    if p.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(ph) = (unsafe { load(p) }) else {
        return sk_status::SK_ERR_DOMAIN;
    };
    let [ox, oy, oz] = out;
    let inputs = [w[0], w[1], w[2], u1, u2];
    let outputs = [(ox, false), (oy, false), (oz, false), (pdf_out, true)];
    if let Err(e) = check_soa(&inputs, &outputs, n) {
        return e;
    }
    if n == 0 {
        return sk_status::SK_OK;
    }
    // SAFETY: checked above: u1 and u2 hold n elements.
    let (u1_s, u2_s) = unsafe {
        (
            core::slice::from_raw_parts(u1, n),
            core::slice::from_raw_parts(u2, n),
        )
    };
    if let Err(e) = check_uniforms(u1_s).and_then(|()| check_uniforms(u2_s)) {
        return e.into();
    }
    let run = |i: &[[S::T; SOA_BLOCK]; 5], o: &mut [[S::T; SOA_BLOCK]; 4], len: usize| {
        let [ix, iy, iz, a, b] = i.each_ref().map(|x| x.get(..len).unwrap_or(&[]));
        let [ox, oy, oz, pdf] = o.each_mut().map(|x| x.get_mut(..len).unwrap_or(&mut []));
        ph.sample_dir_each([ix, iy, iz], a, b, [ox, oy, oz], pdf);
    };
    unsafe { soa_blocks(inputs, [ox, oy, oz, pdf_out], n, run) };
    sk_status::SK_OK
}

/// Isotropic scattering, p = 1/(4 pi).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_isotropic(out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Ok(Phase::isotropic())) }
}

/// Double twin of `sk_phase_isotropic`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_isotropic_f64(out: *mut sk_phase_f64) -> sk_status {
    unsafe { construct(out, Ok(Phase::isotropic())) }
}

/// Rayleigh scattering, p = 3/(16 pi) (1 + mu^2); sampled by exact inversion.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_rayleigh(out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Ok(Phase::rayleigh())) }
}

/// Double twin of `sk_phase_rayleigh`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_rayleigh_f64(out: *mut sk_phase_f64) -> sk_status {
    unsafe { construct(out, Ok(Phase::rayleigh())) }
}

/// Henyey-Greenstein with asymmetry -1 < g < 1 (g > 0 forward).
/// SK_ERR_DOMAIN for |g| >= 1, NaN or inf; SK_ERR_NULL for a NULL `out`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_hg(g: f32, out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Phase::henyey_greenstein(g)) }
}

/// Double twin of `sk_phase_hg`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_hg_f64(g: f64, out: *mut sk_phase_f64) -> sk_status {
    unsafe { construct(out, Phase::henyey_greenstein(g)) }
}

/// Rayleigh scattering with depolarisation factor 0 <= rho < 1 (air: about
/// 0.028); rho = 0 is plain Rayleigh. SK_ERR_DOMAIN outside [0, 1) or NaN.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_rayleigh_depolarized(
    depolarization: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::rayleigh_depolarized(depolarization)) }
}

/// Double twin of `sk_phase_rayleigh_depolarized`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_rayleigh_depolarized_f64(
    depolarization: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::rayleigh_depolarized(depolarization)) }
}

/// Draine's phase function (Jendersie & d'Eon 2023) with -1 < g < 1 and
/// finite alpha >= 0; alpha = 1 is Cornette-Shanks, alpha = 0 is HG. Sampled
/// exactly and accurately on the whole domain. SK_ERR_DOMAIN otherwise.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_draine(g: f32, alpha: f32, out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Phase::draine(g, alpha)) }
}

/// Double twin of `sk_phase_draine`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_draine_f64(
    g: f64,
    alpha: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::draine(g, alpha)) }
}

/// Cornette-Shanks (1992): Draine with alpha = 1; -1 < g < 1.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_cornette_shanks(g: f32, out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Phase::cornette_shanks(g)) }
}

/// Double twin of `sk_phase_cornette_shanks`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_cornette_shanks_f64(g: f64, out: *mut sk_phase_f64) -> sk_status {
    unsafe { construct(out, Phase::cornette_shanks(g)) }
}

/// The fog mixture (1 - w_d) HG(g_hg) + w_d Draine(g_d, alpha):
/// |g_hg| < 1, |g_d| < 1, finite alpha >= 0, 0 <= w_d <= 1, else SK_ERR_DOMAIN.
/// sk_phase_sample_cos inverts the mixture's CDF exactly (monotone);
/// sk_phase_sample_cos_lobe is the paper's cheaper lobe-choice sampler.
/// Construction tabulates seeds for the inverse (about 10 microseconds):
/// build once per medium.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_fog(
    g_hg: f32,
    g_d: f32,
    alpha: f32,
    w_d: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::fog(g_hg, g_d, alpha, w_d)) }
}

/// Double twin of `sk_phase_fog`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_fog_f64(
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
pub unsafe extern "C" fn sk_phase_fournier_forand(
    n: f32,
    mu_j: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::fournier_forand(n, mu_j)) }
}

/// Double twin of `sk_phase_fournier_forand`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_fournier_forand_f64(
    n: f64,
    mu_j: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::fournier_forand(n, mu_j)) }
}

/// Fournier-Forand from the backscatter fraction 0 < b < 1/2 and 1 < n <=
/// 1.8, as oceanographers specify it (nu = -ln(2 b (d90 - 1) + 1) / ln d90,
/// d90 = 2 / (3 (n - 1)^2)); SK_ERR_DOMAIN outside the ranges.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_fournier_forand_backscatter(
    b: f32,
    n: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::fournier_forand_backscatter(b, n)) }
}

/// Double twin of `sk_phase_fournier_forand_backscatter`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_fournier_forand_backscatter_f64(
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
pub unsafe extern "C" fn sk_phase_gegenbauer(alpha: f32, g: f32, out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Phase::gegenbauer(alpha, g)) }
}

/// Double twin of `sk_phase_gegenbauer`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_gegenbauer_f64(
    alpha: f64,
    g: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::gegenbauer(alpha, g)) }
}

/// Two-lobe Henyey-Greenstein, w HG(g1) + (1 - w) HG(g2): |g1| < 1,
/// |g2| < 1, 0 <= w <= 1, else SK_ERR_DOMAIN. The fog mixture with alpha =
/// 0 (sk_phase_get_params reports SK_PHASE_FOG with g_hg = g2, g_d = g1,
/// alpha = 0, w_d = w): sk_phase_sample_cos inverts the mixture's CDF
/// exactly (monotone), sk_phase_sample_cos_lobe picks a lobe with the
/// uniform and reuses it (cheaper, not monotone). Construction takes about
/// 10 microseconds: build once per medium.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_two_lobe_hg(
    g1: f32,
    g2: f32,
    w: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::two_lobe_hg(g1, g2, w)) }
}

/// Double twin of `sk_phase_two_lobe_hg`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_two_lobe_hg_f64(
    g1: f64,
    g2: f64,
    w: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::two_lobe_hg(g1, g2, w)) }
}

/// The fog phase function fitted to Mie scattering by water droplets of
/// diameter 0 < d <= 50 micrometres (Jendersie & d'Eon 2023; four ranges
/// split at 0.1, 1.5 and 5 um). SK_ERR_DOMAIN outside (0, 50] or NaN.
/// Construction takes about 10 microseconds (see sk_phase_fog).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_fog_diameter(diameter_um: f32, out: *mut sk_phase) -> sk_status {
    unsafe { construct(out, Phase::fog_diameter(diameter_um)) }
}

/// Double twin of `sk_phase_fog_diameter`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_fog_diameter_f64(
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
pub unsafe extern "C" fn sk_phase_particle(
    diameter_um: f32,
    tolerance: f32,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { construct(out, Phase::particle(diameter_um, tolerance)) }
}

/// Double twin of `sk_phase_particle`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_particle_f64(
    diameter_um: f64,
    tolerance: f64,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { construct(out, Phase::particle(diameter_um, tolerance)) }
}

/// The models sk_phase_particle_mie chooses from.
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_particle_model {
    /// Uniform over the sphere.
    SK_PARTICLE_ISOTROPIC = 0,
    /// Henyey-Greenstein with the best-fit g.
    SK_PARTICLE_HG = 1,
    /// Rayleigh.
    SK_PARTICLE_RAYLEIGH = 2,
    /// Draine with the best-fit g and alpha.
    SK_PARTICLE_DRAINE = 3,
    /// The fog fit (Jendersie & d'Eon 2023).
    SK_PARTICLE_FOG = 4,
    /// A table of the exact Mie phase function: build it with sk_mie_new,
    /// sk_mie_table_sizes, sk_mie_tabulate and sk_table_measured_f64.
    SK_PARTICLE_MIE_TABLE = 5,
    /// Two Henyey-Greenstein lobes with the best-fit g1, g2 and weight
    /// (considered only without a table).
    SK_PARTICLE_TWO_LOBE_HG = 6,
    /// Fournier-Forand with the best-fit n and nu (considered only without
    /// a table).
    SK_PARTICLE_FOURNIER_FORAND = 7,
}

/// What sk_phase_particle_mie found.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_particle_choice {
    /// The chosen model, an sk_particle_model.
    pub model: u32,
    /// 1 when distance is within the tolerance (without a table none may
    /// be, and the closest model is returned), else 0.
    pub within_tolerance: u32,
    /// The chosen model's total-variation distance to the Mie phase
    /// function (0 for the table, the reference itself; the table built at
    /// sk_mie_table_sizes adds at most 1.2e-3 for x <= 1000).
    pub distance: f64,
    /// Each candidate's best distance: isotropic, HG, Rayleigh, Draine, fog
    /// fit, two-lobe HG, Fournier-Forand (NaN for the fog fit beyond 50 um,
    /// and for the last two when a table is allowed: they are fitted only
    /// without one).
    pub distances: [f64; 7],
    /// The droplets' size parameter.
    pub x: f64,
    /// The refractive index used.
    pub m: super::mie::sk_complex,
    /// The chosen model ready to sample; unconstructed (every query NaN)
    /// for SK_PARTICLE_MIE_TABLE.
    pub phase: sk_phase_f64,
}

/// The sk_complex values sk_phase_particle_mie needs in buf; 0 for input
/// it rejects. m = {0, 0} means water at that wavelength (0.182 to 1.129
/// um).
#[unsafe(no_mangle)]
pub extern "C" fn sk_particle_mie_buffer_len(
    diameter_um: f64,
    wavelength_um: f64,
    m: super::mie::sk_complex,
) -> usize {
    let m = (m.re != 0.0 || m.im != 0.0).then(|| crate::mie::Complex::new(m.re, m.im));
    crate::choose::mie::buffer_len(diameter_um, wavelength_um, m).unwrap_or(0)
}

/// The honest chooser: the cheapest model whose total-variation distance to
/// the exact Mie phase function of droplets of diameter_um micrometres in
/// air at vacuum wavelength wavelength_um is within tolerance (0 <
/// tolerance < 1). m is the droplets' relative index (re + i im, im >= 0
/// absorbs); {0, 0} means water (Daimon & Masumura 2007, 0.182 to 1.129
/// um). Candidates in order of sampling cost: isotropic, HG, Rayleigh, then
/// with allow_table != 0 the Mie table, else Draine, two-lobe HG, the fog
/// fit and Fournier-Forand (each with best-fit parameters). buf
/// holds len >= sk_particle_mie_buffer_len values, work work_len >= 4096
/// doubles. Takes about 0.15 s at x = 300 with a table, 0.25 to 0.4 s
/// without: build once per medium.
/// SK_ERR_NULL for NULL buf, work or out; SK_ERR_DOMAIN for invalid input
/// or overlapping buffers; SK_ERR_SIZE for short buffers. *out is written
/// only on success.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_phase_particle_mie(
    diameter_um: f64,
    wavelength_um: f64,
    m: super::mie::sk_complex,
    tolerance: f64,
    allow_table: u32,
    buf: *mut super::mie::sk_complex,
    len: usize,
    work: *mut f64,
    work_len: usize,
    out: *mut sk_particle_choice,
) -> sk_status {
    use crate::choose::mie::choose_mie;
    use crate::mie::Complex;
    if buf.is_null() || work.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    if !super::fits::<Complex>(len) || !super::fits::<f64>(work_len) {
        return sk_status::SK_ERR_SIZE;
    }
    let bytes = |n: usize, size: usize| n.saturating_mul(size);
    let (b0, w0) = (buf as usize, work as usize);
    let (b1, w1) = (
        b0.saturating_add(bytes(len, 16)),
        w0.saturating_add(bytes(work_len, 8)),
    );
    if b0 < w1 && w0 < b1 {
        return sk_status::SK_ERR_DOMAIN;
    }
    let slices = unsafe {
        (
            super::slice_out(buf.cast::<Complex>(), len),
            super::slice_out(work, work_len),
        )
    };
    let (buf, work) = match slices {
        (Ok(b), Ok(w)) => (b, w),
        (Err(e), _) | (_, Err(e)) => return e,
    };
    let m = (m.re != 0.0 || m.im != 0.0).then(|| Complex::new(m.re, m.im));
    let r = choose_mie(
        diameter_um,
        wavelength_um,
        m,
        tolerance,
        allow_table != 0,
        buf,
        work,
    )
    .map(choice_to_c);
    unsafe { write_result(out, r) }
}

fn choice_to_c(c: crate::choose::mie::MieChoice) -> sk_particle_choice {
    use crate::choose::fog::Model;
    let model = match c.model {
        Model::Isotropic => sk_particle_model::SK_PARTICLE_ISOTROPIC,
        Model::HenyeyGreenstein => sk_particle_model::SK_PARTICLE_HG,
        Model::Rayleigh => sk_particle_model::SK_PARTICLE_RAYLEIGH,
        Model::Draine => sk_particle_model::SK_PARTICLE_DRAINE,
        Model::Fog => sk_particle_model::SK_PARTICLE_FOG,
        Model::TwoLobeHg => sk_particle_model::SK_PARTICLE_TWO_LOBE_HG,
        Model::FournierForand => sk_particle_model::SK_PARTICLE_FOURNIER_FORAND,
        _ => sk_particle_model::SK_PARTICLE_MIE_TABLE,
    };
    sk_particle_choice {
        model: model as u32,
        within_tolerance: u32::from(c.within_tolerance),
        distance: c.distance,
        distances: c.distances,
        x: c.x,
        m: super::mie::sk_complex {
            re: c.m.re,
            im: c.m.im,
        },
        phase: c.phase.map_or(sk_phase_f64::ZEROED, store),
    }
}

/// The cheapest model within total-variation distance `tolerance` (0 <
/// tolerance < 1) of a phase function measured or tabulated at m >= 2
/// cosines, as sk_table_measured_f64 takes it (`cos_theta[j]` strictly
/// monotone within [-1, 1], `pdf[j]` finite and non-negative, any scale;
/// linear in cos theta between the points): a size distribution's Mie
/// average from sk_polydisperse_average, a measured volume scattering
/// function. Candidates as sk_phase_particle_mie without the fog fit
/// (`distances[4]` is NaN); SK_PARTICLE_MIE_TABLE means
/// sk_table_measured_f64 over the same data. x and m of the result are
/// NaN. work holds work_len >= 4096 doubles and must not overlap the data.
/// Takes about 0.25 s without a table: build once per medium. SK_ERR_NULL
/// for NULL pointers; SK_ERR_DOMAIN for a tolerance outside (0, 1), invalid
/// data or overlapping arrays; SK_ERR_SIZE for m < 2 or a short work. *out
/// is written only on success.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_particle_measured(
    cos_theta: *const f64,
    pdf: *const f64,
    m: usize,
    tolerance: f64,
    allow_table: u32,
    work: *mut f64,
    work_len: usize,
    out: *mut sk_particle_choice,
) -> sk_status {
    use crate::choose::mie::choose_measured;
    if cos_theta.is_null() || pdf.is_null() || work.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    if !super::fits::<f64>(m) || !super::fits::<f64>(work_len) {
        return sk_status::SK_ERR_SIZE;
    }
    let range = |p: *const f64, n: usize| {
        let a = p as usize;
        (a, a.saturating_add(n.saturating_mul(8)))
    };
    let w = range(work, work_len);
    let apart = |(a0, a1): (usize, usize)| a1 <= w.0 || w.1 <= a0 || a0 == a1;
    if !(apart(range(cos_theta, m)) && apart(range(pdf, m))) {
        return sk_status::SK_ERR_DOMAIN;
    }
    let slices = unsafe {
        (
            super::slice_in(cos_theta, m),
            super::slice_in(pdf, m),
            super::slice_out(work, work_len),
        )
    };
    let (c, p, work) = match slices {
        (Ok(c), Ok(p), Ok(w)) => (c, p, w),
        (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => return e,
    };
    let r = choose_measured(c, p, tolerance, allow_table != 0, work).map(choice_to_c);
    unsafe { write_result(out, r) }
}

/// cos theta by lobe: for a fog phase, the paper's sampler (u < w_d picks the
/// Draine lobe and u is rescaled and reused inside the lobe): exact in
/// distribution and cheaper than sk_phase_sample_cos, but not monotone in u.
/// For every other phase the same as sk_phase_sample_cos. NaN for a NULL or
/// unconstructed phase.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_lobe(p: *const sk_phase, u: f32) -> f32 {
    unsafe { load(p) }.map_or(f32::NAN, |ph| ph.sample_cos_by_lobe(u))
}

/// Double twin of `sk_phase_sample_cos_lobe`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_lobe_f64(p: *const sk_phase_f64, u: f64) -> f64 {
    unsafe { load(p) }.map_or(f64::NAN, |ph| ph.sample_cos_by_lobe(u))
}

/// Density per steradian at cos_theta. NaN for a NULL or unconstructed phase.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_pdf(p: *const sk_phase, cos_theta: f32) -> f32 {
    unsafe { pdf(p, cos_theta) }
}

/// Double twin of `sk_phase_pdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_pdf_f64(p: *const sk_phase_f64, cos_theta: f64) -> f64 {
    unsafe { pdf(p, cos_theta) }
}

/// Mean cosine (asymmetry parameter). NaN for a NULL or unconstructed phase.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_mean_cosine(p: *const sk_phase) -> f32 {
    unsafe { mean_cosine(p) }
}

/// Double twin of `sk_phase_mean_cosine`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_mean_cosine_f64(p: *const sk_phase_f64) -> f64 {
    unsafe { mean_cosine(p) }
}

/// Inverse CDF: maps u in [0, 1] monotonically to cos theta in [-1, 1]
/// (u = 0 gives -1). u outside [0, 1] is clamped; NaN gives NaN, as does a
/// NULL or unconstructed phase.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos(p: *const sk_phase, u: f32) -> f32 {
    unsafe { sample_cos(p, u) }
}

/// Double twin of `sk_phase_sample_cos`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_f64(p: *const sk_phase_f64, u: f64) -> f64 {
    unsafe { sample_cos(p, u) }
}

/// What `sk_phase_cos_inline_sample` (include/scatterkit_inline.h) needs to
/// draw cos theta without a call into the library: fill it with
/// sk_phase_cos_inline_init, then treat it as read-only. For a
/// Henyey-Greenstein phase on x86, x86-64 and AArch64 (|g| >= 2^-10) it
/// holds the constants of the f32 sampler's double-precision formula, so
/// the inline function returns sk_phase_sample_cos's bits; for every other
/// phase the constants are 0 and the inline function calls
/// sk_phase_sample_cos.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_phase_cos_inline {
    /// k, A and B of cos theta = A - B / (u' + k)^2, computed in double and
    /// rounded once to float; all 0 where the library is called instead.
    pub kab: [f64; 3],
    /// 1 where u' = 1 - u (g <= 0), else 0 (u' = u).
    pub mirror: u32,
    /// Zero.
    pub reserved: u32,
    /// The phase itself, for the calls that go to the library.
    pub phase: sk_phase,
}

/// Fills *out for sk_phase_cos_inline_sample from the phase *p (any model;
/// see sk_phase_cos_inline). SK_ERR_NULL for a NULL pointer; SK_ERR_DOMAIN
/// for an unconstructed phase. *out is written only on SK_OK.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_cos_inline_init(
    p: *const sk_phase,
    out: *mut sk_phase_cos_inline,
) -> sk_status {
    if p.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let r = match unsafe { load(p) } {
        Some(ph) => {
            let (kab, mirror) = match ph {
                Phase::HenyeyGreenstein(h) => h.f64_path_constants().unwrap_or(([0.0; 3], false)),
                _ => ([0.0; 3], false),
            };
            Ok(sk_phase_cos_inline {
                kab,
                mirror: mirror as u32,
                reserved: 0,
                // SAFETY: p is non-NULL and points to an sk_phase.
                phase: unsafe { p.read() },
            })
        }
        None => Err(Error::Domain),
    };
    unsafe { write_result(out, r) }
}

/// CDF: P(cos theta <= cos_theta), the inverse map of `sk_phase_sample_cos`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_cdf(p: *const sk_phase, cos_theta: f32) -> f32 {
    unsafe { cdf(p, cos_theta) }
}

/// Double twin of `sk_phase_cdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_cdf_f64(p: *const sk_phase_f64, cos_theta: f64) -> f64 {
    unsafe { cdf(p, cos_theta) }
}

/// Scattered propagation direction about the unit vector w_in: cos theta =
/// sk_phase_sample_cos(p, u1), azimuth 2 pi u2 in the basis sk_onb(w_in).
/// Writes the direction's density per steradian to pdf_out unless it is NULL.
/// A NULL or unconstructed phase gives NaN (direction and pdf).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_dir(
    p: *const sk_phase,
    w_in: sk_vec3,
    u1: f32,
    u2: f32,
    pdf_out: *mut f32,
) -> sk_vec3 {
    unsafe { sample_dir(p, w_in, u1, u2, pdf_out) }
}

/// Double twin of `sk_phase_sample_dir`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_dir_f64(
    p: *const sk_phase_f64,
    w_in: sk_vec3_f64,
    u1: f64,
    u2: f64,
    pdf_out: *mut f64,
) -> sk_vec3_f64 {
    unsafe { sample_dir(p, w_in, u1, u2, pdf_out) }
}

/// `cos_out[i] = sk_phase_sample_cos(p, u[i])` for `i < n`. `u` and `cos_out`
/// may be the same array; other overlaps give SK_ERR_DOMAIN. SK_ERR_DOMAIN if
/// any `u[i]` is NaN or outside `[0, 1]`, or p is unconstructed; SK_ERR_NULL for NULL
/// p, or NULL arrays with n > 0; SK_ERR_SIZE if n floats cannot exist. On
/// error nothing is written; n = 0 is SK_OK.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_n(
    p: *const sk_phase,
    u: *const f32,
    cos_out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(p, u, cos_out, n) }
}

/// Double twin of `sk_phase_sample_cos_n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_n_f64(
    p: *const sk_phase_f64,
    u: *const f64,
    cos_out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(p, u, cos_out, n) }
}

/// Directions for n rays at once, structure of arrays (the layout of
/// wavefront renderers): for each `i < n`, the direction
/// `sk_phase_sample_dir(p, (w_x[i], w_y[i], w_z[i]), u1[i], u2[i], &pdf)`
/// goes to `(out_x[i], out_y[i], out_z[i])` and its density to `pdf_out[i]`,
/// bit for bit the scalar call's. pdf_out may be NULL. An output array may
/// be the same array as an input (in place); any other overlap, or outputs
/// overlapping each other, is SK_ERR_DOMAIN, as is any `u1[i]` or `u2[i]` NaN
/// or outside [0, 1], or an unconstructed p. SK_ERR_NULL for a NULL p or a
/// NULL array (other than pdf_out) with n > 0; SK_ERR_SIZE if n floats
/// cannot exist. On error nothing is written; n = 0 is SK_OK. The loop runs
/// in blocks of 64 through stack buffers and vectorises for the closed-form
/// phase functions (isotropic, Rayleigh, HG).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_phase_sample_dir_n(
    p: *const sk_phase,
    w_x: *const f32,
    w_y: *const f32,
    w_z: *const f32,
    u1: *const f32,
    u2: *const f32,
    out_x: *mut f32,
    out_y: *mut f32,
    out_z: *mut f32,
    pdf_out: *mut f32,
    n: usize,
) -> sk_status {
    let (w, out) = ([w_x, w_y, w_z], [out_x, out_y, out_z]);
    unsafe { sample_dir_n(p, w, u1, u2, out, pdf_out, n) }
}

/// Double twin of `sk_phase_sample_dir_n`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_phase_sample_dir_n_f64(
    p: *const sk_phase_f64,
    w_x: *const f64,
    w_y: *const f64,
    w_z: *const f64,
    u1: *const f64,
    u2: *const f64,
    out_x: *mut f64,
    out_y: *mut f64,
    out_z: *mut f64,
    pdf_out: *mut f64,
    n: usize,
) -> sk_status {
    let (w, out) = ([w_x, w_y, w_z], [out_x, out_y, out_z]);
    unsafe { sample_dir_n(p, w, u1, u2, out, pdf_out, n) }
}

/// Which phase function an sk_phase holds (its tag, also the value of the
/// enum's discriminant in Rust).
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_phase_model {
    /// Uniform over the sphere: no parameters.
    SK_PHASE_ISOTROPIC = 1,
    /// Rayleigh: no parameters.
    SK_PHASE_RAYLEIGH = 2,
    /// Depolarised Rayleigh: `params[0]` = rho.
    SK_PHASE_RAYLEIGH_DEPOLARIZED = 3,
    /// Henyey-Greenstein: `params[0]` = g.
    SK_PHASE_HG = 4,
    /// Draine (Cornette-Shanks for alpha = 1): `params[0]` = g, `params[1]` = alpha.
    SK_PHASE_DRAINE = 5,
    /// The fog mixture: params = g_hg, g_d, alpha, w_d.
    SK_PHASE_FOG = 6,
    /// The Gegenbauer kernel: `params[0]` = alpha, `params[1]` = g.
    SK_PHASE_GEGENBAUER = 7,
    /// Fournier-Forand: `params[0]` = n, `params[1]` = nu = (3 - Junge
    /// slope)/2, `params[2]` = the backscatter fraction.
    SK_PHASE_FOURNIER_FORAND = 8,
}

/// What an sk_phase holds, for a host to hand to a device: the model (an
/// sk_phase_model) and its parameters (`count` of them, the rest 0).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_phase_params {
    /// An sk_phase_model.
    pub model: u32,
    /// How many of `params` the model uses (0 to 4).
    pub count: u32,
    /// The parameters, in the order sk_phase_model lists them.
    pub params: [f32; 4],
}

/// What an sk_phase_f64 holds; see `sk_phase_params`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_phase_params_f64 {
    /// An sk_phase_model.
    pub model: u32,
    /// How many of `params` the model uses (0 to 4).
    pub count: u32,
    /// The parameters.
    pub params: [f64; 4],
}

/// The model and parameters of a phase, in the order the C enum lists them.
fn model_params<T: Real>(p: &Phase<T>) -> (sk_phase_model, u32, [T; 4]) {
    use sk_phase_model::*;
    let z = T::ZERO;
    match *p {
        Phase::Isotropic(_) => (SK_PHASE_ISOTROPIC, 0, [z; 4]),
        Phase::Rayleigh(_) => (SK_PHASE_RAYLEIGH, 0, [z; 4]),
        Phase::RayleighDepolarized(r) => (SK_PHASE_RAYLEIGH_DEPOLARIZED, 1, [r.rho(), z, z, z]),
        Phase::HenyeyGreenstein(h) => (SK_PHASE_HG, 1, [h.g(), z, z, z]),
        Phase::Draine(d) => (SK_PHASE_DRAINE, 2, [d.g(), d.alpha(), z, z]),
        Phase::Fog(f) => {
            let (a, b, c, d) = f.params();
            (SK_PHASE_FOG, 4, [a, b, c, d])
        }
        Phase::Gegenbauer(k) => (SK_PHASE_GEGENBAUER, 2, [k.alpha(), k.g(), z, z]),
        Phase::FournierForand(f) => (
            SK_PHASE_FOURNIER_FORAND,
            3,
            [f.n(), f.nu(), f.backscatter(), z],
        ),
    }
}

/// Writes `make(model, count, params)` for the phase behind `p` to *out.
unsafe fn get_params<S: PhaseStore>(p: *const S, out: *mut S::Params) -> sk_status {
    if p.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let r = unsafe { load(p) }.ok_or(Error::Domain).map(|ph| {
        let (model, count, params) = model_params(ph);
        S::params(model as u32, count, params)
    });
    unsafe { write_result(out, r) }
}

/// Writes what `p` holds to *out. SK_ERR_NULL for NULL pointers;
/// SK_ERR_DOMAIN for an unconstructed phase (its tag is not a model).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_get_params(
    p: *const sk_phase,
    out: *mut sk_phase_params,
) -> sk_status {
    unsafe { get_params(p, out) }
}

/// Double twin of `sk_phase_get_params`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_get_params_f64(
    p: *const sk_phase_f64,
    out: *mut sk_phase_params_f64,
) -> sk_status {
    unsafe { get_params(p, out) }
}

#[cfg(test)]
mod tag_tests {
    use super::*;

    /// Every model's stored tag is the one `tag_of` lists, in `1..=LAST_TAG`,
    /// and the last variant's is `LAST_TAG`.
    #[test]
    fn tags_match_the_repr() {
        let models: [Phase<f32>; 8] = [
            Phase::isotropic(),
            Phase::rayleigh(),
            Phase::rayleigh_depolarized(0.03).unwrap(),
            Phase::henyey_greenstein(0.7).unwrap(),
            Phase::draine(0.5, 1.0).unwrap(),
            Phase::fog_diameter(2.0).unwrap(),
            Phase::gegenbauer(0.5, 0.7).unwrap(),
            Phase::fournier_forand_backscatter(0.0183, 1.1).unwrap(),
        ];
        for m in &models {
            // SAFETY: Phase is repr(C, u32): it begins with its u32 tag.
            let stored = unsafe { (m as *const Phase<f32>).cast::<u32>().read() };
            assert_eq!(stored, tag_of(m));
            assert!((1..=LAST_TAG).contains(&stored));
        }
        assert_eq!(tag_of(&models[7]), LAST_TAG);
    }
}
