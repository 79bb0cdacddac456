//! Wavelength-dependent phase functions sampled at a hero wavelength.

use super::mixture::part_at;
use super::phase::PhaseStore;
use super::table::TableStore;
use super::{sk_phase, sk_phase_f64, sk_status, sk_table, sk_table_f64};
use crate::error::Error;
use crate::mixture::Part;
use crate::mixture::spectral::{MAX_CHANNELS, SpectralPhase};

/// One channel's phase function: exactly one of phase and table non-NULL.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_channel_phase {
    /// A phase function, or NULL.
    pub phase: *const sk_phase,
    /// A table, or NULL.
    pub table: *const sk_table,
}

/// One channel's phase function (double); see `sk_channel_phase`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_channel_phase_f64 {
    /// A phase function, or NULL.
    pub phase: *const sk_phase_f64,
    /// A table, or NULL.
    pub table: *const sk_table_f64,
}

/// A C channel type with its phase and table types.
trait ChannelStore: Copy {
    type P: PhaseStore;
    type Tb: TableStore<T = <Self::P as PhaseStore>::T>;
    fn pair(&self) -> (*const Self::P, *const Self::Tb);
}
impl ChannelStore for sk_channel_phase {
    type P = sk_phase;
    type Tb = sk_table;
    fn pair(&self) -> (*const sk_phase, *const sk_table) {
        (self.phase, self.table)
    }
}
impl ChannelStore for sk_channel_phase_f64 {
    type P = sk_phase_f64;
    type Tb = sk_table_f64;
    fn pair(&self) -> (*const sk_phase_f64, *const sk_table_f64) {
        (self.phase, self.table)
    }
}

type T<C> = <<C as ChannelStore>::P as PhaseStore>::T;

/// The channels and the caller's output slice.
type Loaded<'a, C> = (SpectralPhase<'a, T<C>>, &'a mut [T<C>]);

/// The Rust channels behind `ch[0]` to `ch[k - 1]` and the output slice of `k`
/// values at `out`.
unsafe fn channels<'a, C: ChannelStore>(
    ch: *const C,
    k: usize,
    out: *mut T<C>,
) -> Result<Loaded<'a, C>, sk_status> {
    if ch.is_null() || out.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    if k == 0 || k > MAX_CHANNELS {
        return Err(sk_status::SK_ERR_SIZE);
    }
    // SAFETY: ch points to k readable channels and out to k writable
    // values (the caller's contract).
    let given = unsafe { core::slice::from_raw_parts(ch, k) };
    let filler = Part::Phase(crate::phase::Phase::isotropic());
    let mut parts = [filler; MAX_CHANNELS];
    for (slot, c) in parts.iter_mut().zip(given) {
        let (p, t) = c.pair();
        *slot = unsafe { part_at(p, t) }?;
    }
    let s = SpectralPhase::new(parts.get(..k).unwrap_or(&[])).map_err(sk_status::from)?;
    Ok((s, unsafe { core::slice::from_raw_parts_mut(out, k) }))
}

unsafe fn sample<C: ChannelStore>(
    (ch, k): (*const C, usize),
    (hero, u): (usize, T<C>),
    cos_out: *mut T<C>,
    ratio_out: *mut T<C>,
) -> sk_status {
    if cos_out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let run = || -> Result<T<C>, sk_status> {
        let (s, ratio) = unsafe { channels(ch, k, ratio_out) }?;
        s.sample_cos(hero, u, ratio).map_err(sk_status::from)
    };
    match run() {
        Ok(mu) => {
            // SAFETY: checked non-NULL above.
            unsafe { cos_out.write(mu) };
            sk_status::SK_OK
        }
        Err(e) => e,
    }
}

unsafe fn pdf<C: ChannelStore>(
    (ch, k): (*const C, usize),
    mu: T<C>,
    pdf_out: *mut T<C>,
) -> sk_status {
    match unsafe { channels(ch, k, pdf_out) } {
        Ok((s, out)) => match s.pdf(mu, out) {
            Ok(()) => sk_status::SK_OK,
            Err(e) => Error::into(e),
        },
        Err(e) => e,
    }
}

/// cos theta drawn from channel hero's phase function at u (its own
/// sampler), and every channel's ratio p_c(cos theta) / p_hero(cos theta)
/// into `ratio_out[0]` to `ratio_out[k - 1]` (1 for the hero): the channel's throughput
/// factor. With the hero drawn uniformly, ratio_c / mean(ratio) is the
/// one-sample balance heuristic over the hero: unbiased and at most k.
/// SK_ERR_NULL for NULL pointers or a channel with neither phase nor
/// table; SK_ERR_SIZE for k = 0, k > 16, hero >= k or a malformed table;
/// SK_ERR_DOMAIN for a channel with both, an unconstructed phase, a NaN u
/// or a cos theta where the hero's density is 0. Nothing written on error.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_spectral_phase_sample(
    ch: *const sk_channel_phase,
    k: usize,
    hero: usize,
    u: f32,
    cos_out: *mut f32,
    ratio_out: *mut f32,
) -> sk_status {
    unsafe { sample((ch, k), (hero, u), cos_out, ratio_out) }
}

/// Double twin of `sk_spectral_phase_sample`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_spectral_phase_sample_f64(
    ch: *const sk_channel_phase_f64,
    k: usize,
    hero: usize,
    u: f64,
    cos_out: *mut f64,
    ratio_out: *mut f64,
) -> sk_status {
    unsafe { sample((ch, k), (hero, u), cos_out, ratio_out) }
}

/// Every channel's density per steradian at cos_theta into pdf_out[0 ..
/// k], for light-sampled directions. Errors as sk_spectral_phase_sample.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_spectral_phase_pdf(
    ch: *const sk_channel_phase,
    k: usize,
    cos_theta: f32,
    pdf_out: *mut f32,
) -> sk_status {
    unsafe { pdf((ch, k), cos_theta, pdf_out) }
}

/// Double twin of `sk_spectral_phase_pdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_spectral_phase_pdf_f64(
    ch: *const sk_channel_phase_f64,
    k: usize,
    cos_theta: f64,
    pdf_out: *mut f64,
) -> sk_status {
    unsafe { pdf((ch, k), cos_theta, pdf_out) }
}
