//! Spectral media: hero-wavelength tracking through density majorants.

use super::majorant::{MajStore, load_maj};
use super::medium::{GridStore, load};
use super::{CRng, CVec, overlaps, sk_rng, sk_status, sk_vec3, sk_vec3_f64, slice_in, slice_out};
use crate::medium::Ray;
use crate::medium::spectral::{MAX_CHANNELS, Ratios, Spectrum};

/// The channels (wavelength samples) of a spectral medium: coefficients per
/// unit density, `channels` of each (1 to 16), and the hero channel whose
/// majorant draws the free paths.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_spectrum {
    /// sigma_a per unit density, one per channel, finite and >= 0.
    pub sigma_a: *const f32,
    /// sigma_s per unit density, one per channel, finite and >= 0.
    pub sigma_s: *const f32,
    /// Number of channels, 1 to 16.
    pub channels: usize,
    /// The hero channel, < channels.
    pub hero: u32,
}

/// The channels of a spectral medium (double); see `sk_spectrum`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_spectrum_f64 {
    /// sigma_a per unit density.
    pub sigma_a: *const f64,
    /// sigma_s per unit density.
    pub sigma_s: *const f64,
    /// Number of channels, 1 to 16.
    pub channels: usize,
    /// The hero channel, < channels.
    pub hero: u32,
}

/// A C spectrum type and its float.
pub(crate) trait SpecStore: Copy {
    type T;
    fn parts(&self) -> (*const Self::T, *const Self::T, usize, u32);
}

macro_rules! impl_spec_store {
    ($c:ty, $t:ty) => {
        impl SpecStore for $c {
            type T = $t;
            fn parts(&self) -> (*const $t, *const $t, usize, u32) {
                (self.sigma_a, self.sigma_s, self.channels, self.hero)
            }
        }
    };
}
impl_spec_store!(sk_spectrum, f32);
impl_spec_store!(sk_spectrum_f64, f64);

/// Both spectral calls: validates the pointers, builds the Rust views and
/// runs `f`, whose ratios go straight to the caller's arrays (the Rust
/// layer writes them only on success).
#[allow(clippy::too_many_arguments)]
unsafe fn spectral<G, S, P>(
    m: *const S,
    g: *const G,
    spec: *const P,
    rng: *mut sk_rng,
    (weight, r_u, r_l): (*mut G::T, *mut G::T, *mut G::T),
    f: impl FnOnce(
        &crate::medium::majorant::Majorants<'_, G::T>,
        &crate::medium::Grid<'_, G::T>,
        &Spectrum<'_, G::T>,
        &mut CRng,
        &mut Ratios<'_, G::T>,
    ) -> sk_status,
) -> sk_status
where
    G: GridStore,
    S: MajStore<T = G::T, V = G::V>,
    P: SpecStore<T = G::T>,
{
    if g.is_null() || spec.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(mut r) = (unsafe { CRng::from_ptr(rng) }) else {
        return sk_status::SK_ERR_NULL;
    };
    // SAFETY: non-NULL spec points to an sk_spectrum (module contract).
    let (sa, ss, n, hero) = unsafe { &*spec }.parts();
    if n == 0 || n > MAX_CHANNELS {
        return sk_status::SK_ERR_SIZE;
    }
    let maj = match unsafe { load_maj(m) } {
        Ok(x) => x,
        Err(e) => return e,
    };
    let Some(grid) = (unsafe { load(g) }) else {
        return sk_status::SK_ERR_SIZE;
    };
    // The outputs are written through &mut slices: none may alias an input
    // or another output.
    for out in [weight, r_u, r_l] {
        if overlaps(out, sa, n) || overlaps(out, ss, n) {
            return sk_status::SK_ERR_OVERLAP;
        }
    }
    if overlaps(weight, r_u, n) || overlaps(weight, r_l, n) || overlaps(r_u, r_l, n) {
        return sk_status::SK_ERR_OVERLAP;
    }
    let views = unsafe {
        (
            slice_in(sa, n),
            slice_in(ss, n),
            slice_out(weight, n),
            slice_out(r_u, n),
            slice_out(r_l, n),
        )
    };
    let (sa, ss, w, u, l) = match views {
        (Ok(a), Ok(b), Ok(c), Ok(d), Ok(e)) => (a, b, c, d, e),
        (Err(e), ..) | (_, Err(e), ..) | (_, _, Err(e), ..) | (.., Err(e), _) | (.., Err(e)) => {
            return e;
        }
    };
    let s = Spectrum {
        sigma_a: sa,
        sigma_s: ss,
        hero: hero as usize,
    };
    let mut out = Ratios {
        weight: w,
        r_u: u,
        r_l: l,
    };
    f(&maj, &grid, &s, &mut r, &mut out)
}

#[allow(clippy::too_many_arguments)]
unsafe fn delta<G, S, P>(
    m: *const S,
    g: *const G,
    spec: *const P,
    (o, d, t_max): (G::V, G::V, G::T),
    budget: u32,
    rng: *mut sk_rng,
    out: *mut S::Track,
    ratios: (*mut G::T, *mut G::T, *mut G::T),
) -> sk_status
where
    G: GridStore,
    S: MajStore<T = G::T, V = G::V>,
    P: SpecStore<T = G::T>,
{
    if out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    unsafe {
        spectral(m, g, spec, rng, ratios, |maj, grid, s, r, rat| {
            match maj.delta_track_spectral(
                grid,
                s,
                Ray::new(o.to_vec(), d.to_vec(), t_max),
                budget,
                r,
                rat,
            ) {
                Ok(t) => {
                    out.write(S::track(t));
                    sk_status::SK_OK
                }
                Err(e) => e.into(),
            }
        })
    }
}

#[allow(clippy::too_many_arguments)]
unsafe fn ratio<G, S, P>(
    m: *const S,
    g: *const G,
    spec: *const P,
    (o, d, t_max): (G::V, G::V, G::T),
    budget: u32,
    rng: *mut sk_rng,
    steps_out: *mut u32,
    ratios: (*mut G::T, *mut G::T, *mut G::T),
) -> sk_status
where
    G: GridStore,
    S: MajStore<T = G::T, V = G::V>,
    P: SpecStore<T = G::T>,
{
    unsafe {
        spectral(m, g, spec, rng, ratios, |maj, grid, s, r, rat| {
            match maj.ratio_track_spectral(
                grid,
                s,
                Ray::new(o.to_vec(), d.to_vec(), t_max),
                budget,
                r,
                rat,
            ) {
                Ok(steps) => {
                    if let Some(p) = steps_out.as_mut() {
                        *p = steps;
                    }
                    sk_status::SK_OK
                }
                Err(e) => e.into(),
            }
        })
    }
}

/// Spectral delta tracking (pbrt-v4's hero-wavelength tracking) through
/// grid g's density, walking density majorants m (sk_majorants_build on a
/// grid with sigma_a + sigma_s = 1, or sk_majorants_new; same box as g),
/// with the channels of *s: free paths at the hero's majorant; one uniform
/// picks absorption, scattering or a null collision with the hero's
/// probabilities; every channel's ratios are updated as pbrt-v4 does.
/// Writes *out (the event, its distance or the exit, the tentative
/// collisions) and `weight[c]`, `r_u[c]`, `r_l[c]` for each channel c: with the
/// hero drawn uniformly among the channels, `weight[c]` / mean(r_u) on each
/// event is an unbiased estimate for channel c. Errors as
/// sk_delta_track_majorants, and SK_ERR_SIZE for 0 or more than 16
/// channels; SK_ERR_DOMAIN for a negative or non-finite coefficient, a hero
/// out of range; SK_ERR_OVERLAP for output arrays that overlap an input or
/// each other.
/// Nothing is written on failure.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track_spectral(
    m: *const super::sk_majorants,
    g: *const super::sk_grid,
    s: *const sk_spectrum,
    o: sk_vec3,
    d: sk_vec3,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_track_result,
    weight: *mut f32,
    r_u: *mut f32,
    r_l: *mut f32,
) -> sk_status {
    unsafe { delta(m, g, s, (o, d, t_max), budget, rng, out, (weight, r_u, r_l)) }
}

/// Double twin of `sk_delta_track_spectral`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track_spectral_f64(
    m: *const super::sk_majorants_f64,
    g: *const super::sk_grid_f64,
    s: *const sk_spectrum_f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_track_result_f64,
    weight: *mut f64,
    r_u: *mut f64,
    r_l: *mut f64,
) -> sk_status {
    unsafe { delta(m, g, s, (o, d, t_max), budget, rng, out, (weight, r_u, r_l)) }
}

/// Spectral ratio tracking (arguments as sk_delta_track_spectral): every
/// tentative collision is a null one; weight is pbrt-v4's T_ray (with its
/// Russian roulette), and with the hero drawn uniformly among the channels
/// `weight[c]` / mean(r_l) is an unbiased transmittance estimate for channel
/// c. Writes the tentative collisions to *steps_out unless it is NULL.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track_spectral(
    m: *const super::sk_majorants,
    g: *const super::sk_grid,
    s: *const sk_spectrum,
    o: sk_vec3,
    d: sk_vec3,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    steps_out: *mut u32,
    weight: *mut f32,
    r_u: *mut f32,
    r_l: *mut f32,
) -> sk_status {
    let out = (weight, r_u, r_l);
    unsafe { ratio(m, g, s, (o, d, t_max), budget, rng, steps_out, out) }
}

/// Double twin of `sk_ratio_track_spectral`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track_spectral_f64(
    m: *const super::sk_majorants_f64,
    g: *const super::sk_grid_f64,
    s: *const sk_spectrum_f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    steps_out: *mut u32,
    weight: *mut f64,
    r_u: *mut f64,
    r_l: *mut f64,
) -> sk_status {
    let out = (weight, r_u, r_l);
    unsafe { ratio(m, g, s, (o, d, t_max), budget, rng, steps_out, out) }
}
