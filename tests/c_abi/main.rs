//! The C ABI: the examples and test programs in C and C++ built against
//! the static library and run, the bad-input matrix, sanitizers and
//! valgrind, the exported symbols against the header, the header-only
//! table lookup, and the golden bits through Rust and C. (The header's own
//! regeneration is `dev/tests/generated_header.rs`.)

#[path = "../common/mod.rs"]
mod common;

mod examples_and_programs;
mod golden;
mod matrix;
mod portable;
mod sanitize;
mod symbols;
mod table_header;
mod verbs;
