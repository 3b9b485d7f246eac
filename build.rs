//! Links the `rocking` binary position-dependent (`-no-pie`) on Linux.
//!
//! A position-independent executable is relocated by the dynamic loader
//! at every start: about 40 000 pointers in `.data.rel.ro` (the vtables and
//! string tables of the CLI and, with `gui`, of egui and wgpu), each
//! written through a copy-on-write page fault, about 170 faults and half a
//! millisecond of CPU per process. A sweep that runs one `rocking --batch`
//! per point pays that for every point; linked at a fixed address the
//! binary starts with those pages still shared with the page cache. The
//! price is that the executable itself (not its libraries, heap or stack)
//! is loaded at the same address every time (no ASLR for it).
//!
//! Only the binaries are linked so (`rustc-link-arg-bins`): the library,
//! its tests and the Python extension stay position-independent.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let env = std::env::var("CARGO_CFG_TARGET_ENV").unwrap_or_default();
    // The cc/clang driver that Rust links with on Linux takes -no-pie.
    if os == "linux" && env == "gnu" {
        println!("cargo::rustc-link-arg-bins=-no-pie");
    }
}
