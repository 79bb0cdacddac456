//! The crate's error type; the C layer maps it onto `sk_status`.

use core::fmt;

/// Why a constructor or checked call refused its input.
///
/// Rust returns `Result<_, Error>` where C returns `sk_status`: `Domain` is
/// `SK_ERR_DOMAIN`, `Size` is `SK_ERR_SIZE`, `Method` is `SK_ERR_METHOD`,
/// `Budget` is `SK_ERR_BUDGET` (`SK_ERR_NULL` exists only in C). Variants
/// may be added: match with a wildcard arm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is NaN, infinite, or outside the documented domain.
    Domain,
    /// A buffer is too small, a count is zero where it must not be, or two
    /// slices that must have the same length do not.
    Size,
    /// An enum-valued input (sampling method, table kind, ...) is out of range.
    Method,
    /// An iterative walk (volume tracking) used up its step budget before it
    /// could answer: the medium is optically too thick for the budget along
    /// this ray, or its majorant too loose. No result is biased by a cut.
    Budget,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Error::Domain => "parameter outside its domain",
            Error::Size => "buffer or count of the wrong size",
            Error::Method => "unknown method or kind",
            Error::Budget => "step budget used up",
        })
    }
}

impl core::error::Error for Error {}

/// `TryFrom<u32>` for a fieldless `#[repr(u32)]` enum (how C passes enums):
/// each listed variant matches its own discriminant, any other value is
/// [`Error::Method`]. Leaving a variant out does not compile (and listing
/// one twice is an unreachable-pattern warning).
macro_rules! try_from_u32 {
    ($ty:ident: $($v:ident),+ $(,)?) => {
        impl TryFrom<u32> for $ty {
            type Error = $crate::error::Error;
            fn try_from(v: u32) -> Result<Self, Self::Error> {
                // Exhaustive: a variant missing from the list is an error here.
                const _: fn($ty) = |x| match x {
                    $($ty::$v => (),)+
                };
                $(if v == $ty::$v as u32 {
                    return Ok($ty::$v);
                })+
                Err($crate::error::Error::Method)
            }
        }
    };
}
pub(crate) use try_from_u32;
