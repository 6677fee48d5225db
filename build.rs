//! The lessons are compiled into the library (`src/lessons/builtin.rs`): a change to any file
//! under `lessons/` rebuilds it.
//!
//! A build whose RUSTFLAGS tune LLVM for 256-bit vectors (`-C target-feature=+prefer-256-bit`)
//! keeps the fast wing's x86-64-v4 copy out of 512-bit registers, which makes that copy the
//! fastest on Intel processors too: the cfg `raytree_v4_in_256_bits` tells
//! `fast::simd::preferred_level` so.

fn main() {
    println!("cargo::rerun-if-changed=lessons");
    println!("cargo::rustc-check-cfg=cfg(raytree_v4_in_256_bits)");
    let flags = std::env::var("CARGO_ENCODED_RUSTFLAGS").unwrap_or_default();
    if flags
        .split('\x1f')
        .any(|flag| flag.contains("+prefer-256-bit"))
    {
        println!("cargo::rustc-cfg=raytree_v4_in_256_bits");
    }
}
