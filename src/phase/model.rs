//! What the registry of models (`any.rs`) needs of each model: its
//! parameters as the C API reports them, a constructor from them, the same
//! model in another precision, and the Draine lobes whose Legendre moments
//! have a closed form. Every method is required, so a new model that
//! forgets one does not compile.

use super::PhaseFunction;
use crate::error::Error;
use crate::math::real::Real;

/// Up to two Draine lobes `((g₁, α₁), (g₂, α₂), w₂)` (the second with
/// weight `w₂`): what [`closed_form`](super::moments::closed_form) needs.
pub type Lobes = ((f64, f64), (f64, f64), f64);

/// A phase-function model the [`Phase`](super::Phase) registry holds.
pub trait Model<T: Real>: PhaseFunction<T> + Copy + core::fmt::Debug + PartialEq {
    /// The same model in precision `U`.
    type In<U: Real>: Model<U>;
    /// How many parameters it has (at most 4).
    const PARAMS: usize;
    /// Its parameters, in the order the C API's `sk_phase_get_params`
    /// reports them, the rest 0.
    fn params(&self) -> [T; 4];
    /// The model from exactly [`PARAMS`](Self::PARAMS) parameters as
    /// [`params`](Self::params) reports them (its inverse), checked as its
    /// own constructor checks them: [`Error::Size`] for another count,
    /// [`Error::Domain`] for values out of range.
    fn from_params(p: &[T]) -> Result<Self, Error>;
    /// The same model in `U`: parameters rounded, a parameter that must
    /// stay below 1 in magnitude kept below it.
    fn cast<U: Real>(&self) -> Self::In<U>;
    /// Its Draine lobes if its Legendre moments have a closed form, else
    /// `None` (they are then computed by quadrature).
    fn lobes(&self) -> Option<Lobes>;
}

/// `x` in `U`.
pub(crate) fn to<T: Real, U: Real>(x: T) -> U {
    U::from_f64(x.to_f64())
}

/// `x` in `U`, kept inside `(−1, 1)` (a value that rounds onto ±1 becomes
/// the largest below it in magnitude).
pub(crate) fn open<T: Real, U: Real>(x: T) -> U {
    let y = U::from_f64(x.to_f64());
    if y.abs() < U::ONE {
        y
    } else {
        (U::ONE - U::EPSILON * U::HALF).copysign(y)
    }
}

/// The first `N` of `p` if it holds exactly `N`, else [`Error::Size`].
pub(crate) fn exactly<T: Copy + Default, const N: usize>(p: &[T]) -> Result<[T; N], Error> {
    if p.len() != N {
        return Err(Error::Size);
    }
    let mut out = [T::default(); N];
    out.copy_from_slice(p);
    Ok(out)
}
