//! Fuzz target `draco_decode` (see common/mod.rs, shared with the regression test): a Draco stream in
//! a one-primitive .glb gives a Scene or an error, never a panic, an abort, a hang or a huge allocation.
#![no_main]

mod common;

libfuzzer_sys::fuzz_target!(|data: &[u8]| common::draco(data));
