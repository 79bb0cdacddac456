//! Checked once, loaded in constant time: how the C layer keeps a value it
//! built (a mixture, say) inside a caller's opaque struct.
//!
//! A constructor validates its inputs, builds the Rust value and writes it
//! after a tag that names the type; every later call checks the tag (a
//! NULL, zeroed, misaligned or never-constructed struct gives NaN or an
//! error, never undefined behaviour) and borrows the value in place, with
//! no copy and no rescan. The C type is plain storage (`uint64_t
//! opaque[N]`): copy it freely; its bytes are private, and some of them
//! are padding a constructor need not define (compare values by what they
//! answer, not with memcmp).

/// A C type that stores a `Value` after a tag.
pub(crate) trait Slot: Copy {
    /// What it stores.
    type Value: Copy + 'static;
    /// Written before the value: non-zero, one per C type.
    const TAG: u32;
    /// The type with every byte zero.
    const ZEROED: Self;
    /// Compile-time proof that the value fits (evaluate it in `store`).
    const FITS: () = assert!(
        core::mem::size_of::<Tagged<Self::Value>>() <= core::mem::size_of::<Self>()
            && core::mem::align_of::<Tagged<Self::Value>>() <= core::mem::align_of::<Self>()
    );
}

/// The layout inside a [`Slot`].
#[repr(C)]
#[derive(Clone, Copy)]
struct Tagged<V> {
    tag: u32,
    value: V,
}

/// `value` in a fresh slot (bytes past it zero; padding inside it is
/// not defined).
pub(crate) fn store<S: Slot>(value: S::Value) -> S {
    let () = S::FITS;
    let mut s = S::ZEROED;
    // SAFETY: `Tagged<S::Value>` fits in `S` in size and alignment (FITS),
    // and `S` is plain storage.
    unsafe {
        (&mut s as *mut S)
            .cast::<Tagged<S::Value>>()
            .write(Tagged { tag: S::TAG, value })
    };
    s
}

/// The value in the slot at `p`, or `None` if `p` is NULL, misaligned or
/// does not carry `S`'s tag.
#[inline(always)]
pub(crate) unsafe fn load<'a, S: Slot>(p: *const S) -> Option<&'a S::Value> {
    let () = S::FITS;
    if p.is_null() || !p.is_aligned() {
        return None;
    }
    // SAFETY: `p` points to an `S` (module contract), which begins with the
    // u32 tag; an `S` with this tag was written by `store`.
    let tag = unsafe { p.cast::<u32>().read() };
    if tag != S::TAG {
        return None;
    }
    Some(unsafe { &(*p.cast::<Tagged<S::Value>>()).value })
}
