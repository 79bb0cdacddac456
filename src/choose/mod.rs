//! Model no more than the scene needs: choosers that return the cheapest
//! phase function within a total-variation distance of a reference, the
//! fog fit for a droplet diameter ([`fog`]) or the exact Mie phase function
//! and measured data ([`mie`]). They stand above every model.

pub mod fog;
pub mod mie;
