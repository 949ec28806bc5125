//! Fuzz target `glb_load` (see common/mod.rs, shared with the regression test): any input gives a
//! Scene or an error, never a panic, a hang or a huge allocation.
#![no_main]

mod common;

libfuzzer_sys::fuzz_target!(|data: &[u8]| common::glb(data));
