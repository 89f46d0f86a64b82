//! Build script: with `GLINT_SKIP_GPU=1` in the environment at build time, the test
//! binaries are compiled with `cfg(glint_skip_gpu)`, under which each GPU test carries
//! `#[ignore]` and so reports as ignored, not as passed (see docs/testing.md).

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-env-changed=GLINT_SKIP_GPU");
    println!("cargo::rustc-check-cfg=cfg(glint_skip_gpu)");
    if std::env::var_os("GLINT_SKIP_GPU").is_some_and(|v| v == "1") {
        println!("cargo::rustc-cfg=glint_skip_gpu");
    }
}
