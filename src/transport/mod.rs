//! Light transport through whole layers by the library's own samplers:
//! what a layer of a medium reflects, as material models specify it.

pub mod albedo;
