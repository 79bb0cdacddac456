//! Nothing: this package exists for its test (`tests/generated_header.rs`)
//! and its benchmark (`../benches/samplers.rs`), so that their dependencies
//! stay out of the library's own build.
#![no_std]
