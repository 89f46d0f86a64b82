//! Shared by the GPU tests: a device (or a reason to skip, which fails under CI), scenes
//! from Lua source, and a seeded RNG.

#![allow(dead_code)]

use glint::gpu::GpuContext;
use glint::pack::{pack, PackedScene};
use glint::scene::flatten::flatten;
use glint::scene::lua::{run_scene_file, run_scene_source, ScriptConfig};
use glint::scene::{OptionOverrides, RenderRequest, SceneGraph};
use std::path::{Path, PathBuf};

/// A device on the default (Vulkan) adapter; None (with the reason printed) when there is
/// none — except under CI (`CI` set), where a missing adapter fails the test: CI installs
/// lavapipe, so a skip there would pass vacuously.
pub fn gpu_context() -> Option<GpuContext> {
    match GpuContext::new(None) {
        Ok(ctx) => Some(ctx),
        Err(e) => {
            if std::env::var_os("CI").is_some() {
                panic!("CI is set but no GPU adapter is usable: {e}");
            }
            eprintln!("skipping GPU test: {e}");
            None
        }
    }
}

/// The CS488 corpus folder.
pub fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/cs488/a4-2021plus")
}

fn pack_request(
    graph: &SceneGraph,
    request: &RenderRequest,
    overrides: &OptionOverrides,
) -> PackedScene {
    let mut request = request.clone();
    overrides.apply(&mut request.options);
    request.width = overrides.width.unwrap_or(request.width);
    request.height = overrides.height.unwrap_or(request.height);
    let scene = flatten(graph, &request).expect("flatten");
    pack(&scene).expect("pack")
}

/// Packed scenes of every gr.render in a Lua source, with `overrides` applied.
pub fn packed_from_source(source: &str, overrides: &OptionOverrides) -> Vec<PackedScene> {
    let mut out = Vec::new();
    run_scene_source(
        "test.lua",
        source,
        &corpus(),
        &ScriptConfig::default(),
        &mut |g, r| {
            out.push(pack_request(g, r, overrides));
            Ok(())
        },
    )
    .unwrap_or_else(|e| panic!("{e}\n{source}"));
    out
}

/// Packed scenes of every gr.render in a corpus file, with `overrides` applied.
pub fn packed_from_file(path: &Path, overrides: &OptionOverrides) -> Vec<PackedScene> {
    let mut out = Vec::new();
    run_scene_file(path, &ScriptConfig::default(), &mut |g, r| {
        out.push(pack_request(g, r, overrides));
        Ok(())
    })
    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    out
}

/// xorshift64*: small, seeded, reproducible.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545F4914F6CDD1D)
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }
}
