//! The glint binary: parse the command line, run it, print the error chain and exit non-zero on failure.

fn main() {
    // Built for x86-64-v3 (`.cargo/config.toml`), the binary would die of an illegal instruction
    // somewhere on an older CPU; this says why before it gets there. (CPUID itself: with the
    // features enabled at compile time, `is_x86_feature_detected!` answers yes without asking.)
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
    if !cpu_has_avx2_and_fma() {
        eprintln!(
            "error: this glint was built for x86-64-v3 (AVX2 and FMA), which this CPU lacks; \
             rebuild it with RUSTFLAGS=\"-C target-cpu=x86-64\" cargo build --release"
        );
        std::process::exit(1);
    }
    if let Err(e) = glint::cli::main() {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

/// Whether the CPU has AVX2 and FMA, and the OS saves the AVX registers (CPUID leaves 1 and 7).
#[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
fn cpu_has_avx2_and_fma() -> bool {
    use std::arch::x86_64::{__cpuid, __cpuid_count};
    // CPUID exists on every x86-64 CPU; leaf 7 is asked for only where leaf 0 lists it.
    let max = __cpuid(0).eax;
    let l1 = __cpuid(1).ecx;
    let l7 = if max >= 7 { __cpuid_count(7, 0).ebx } else { 0 };
    let fma = l1 & (1 << 12) != 0;
    let osxsave = l1 & (1 << 27) != 0;
    let avx2 = l7 & (1 << 5) != 0;
    fma && osxsave && avx2
}
