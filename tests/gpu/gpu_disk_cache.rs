//! The on-disk pipeline cache (`src/gpu/device/disk_cache.rs`) on a device: a second run
//! reuses every file and writes nothing; a truncated, corrupted or foreign file is
//! ignored (never trusted), the image is still byte for byte the uncached one, and the
//! file is replaced by one that the next run reuses; runs on several threads at once
//! leave only valid files. (The switch and the folder from the environment are checked
//! end to end in `tests/cli/pipeline_cache.rs`.) Each "run" is a
//! fresh context (its in-memory pipelines empty), as a new process would be.

use crate::common;

use common::{gpu_context, packed_from_source};
use glint::gpu::device::disk_cache::{encode, DiskCache, HEADER_LEN};
use glint::gpu::{render_gpu, GpuRenderInfo, GpuRenderOptions};
use glint::pack::PackedScene;
use glint::scene::{AaMode, OptionOverrides};
use glint::testing::scratch::temp_dir;
use std::collections::BTreeMap;
use std::path::Path;
use std::time::SystemTime;

const SCENE: &str = "
    red = gr.material({0.8, 0.2, 0.2}, {0.5, 0.5, 0.5}, 40)
    root = gr.node('root')
    s = gr.sphere('s') s:translate(0, 0, -4) s:set_material(red) root:add_child(s)
    l = gr.light({-4, 3, 2}, {0.9, 0.9, 0.9}, {1, 0, 0})
    gr.render(root, 'cache.png', 32, 32, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 50,
              {0.1, 0.1, 0.1}, {l})
";

/// Adaptive AA: five pipelines (corners, decide, midpoints, work arguments, integrate).
const PIPELINES: u32 = 5;

fn scene() -> PackedScene {
    let overrides = OptionOverrides {
        aa: Some(AaMode::Adaptive),
        ..OptionOverrides::default()
    };
    packed_from_source(SCENE, &overrides).remove(0)
}

/// One run on a fresh context with `cache`: the film's bits and the render's info.
fn run(cache: impl FnOnce(&wgpu::AdapterInfo) -> DiskCache) -> Option<(Vec<u32>, GpuRenderInfo)> {
    let mut ctx = gpu_context()?;
    let cache = cache(&ctx.info);
    ctx.set_disk_cache(cache);
    let render = render_gpu(&ctx, &scene(), &GpuRenderOptions::default()).unwrap();
    let c = &render.info.compile;
    eprintln!(
        "{} reused, {} written, {} rejected, {} uncached",
        c.reused, c.written, c.rejected, c.uncached
    );
    let bits = render.film.pixels.iter().flatten().map(|c| c.to_bits());
    Some((bits.collect(), render.info))
}

/// Every file of `dir`: name → (bytes, modification time).
fn files(dir: &Path) -> BTreeMap<String, (Vec<u8>, SystemTime)> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return BTreeMap::new();
    };
    entries
        .map(|e| {
            let e = e.unwrap();
            let bytes = std::fs::read(e.path()).unwrap();
            let modified = e.metadata().unwrap().modified().unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                (bytes, modified),
            )
        })
        .collect()
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn a_second_run_reuses_every_file_and_writes_nothing() {
    let dir = temp_dir("disk-cache-reuse");
    let cache_dir = dir.join("glint");
    let Some((first_film, first)) = run(|info| DiskCache::at(&cache_dir, info)) else {
        return;
    };
    assert_eq!(first.compile.written, PIPELINES, "{:?}", first.compile);
    let written = files(&cache_dir);
    assert_eq!(written.len(), PIPELINES as usize, "{:?}", written.keys());
    let (second_film, second) = run(|info| DiskCache::at(&cache_dir, info)).unwrap();
    assert_eq!(
        (
            second.compile.reused,
            second.compile.written,
            second.compile.rejected
        ),
        (PIPELINES, 0, 0),
        "{:?}",
        second.compile
    );
    let names: Vec<&String> = written.keys().collect();
    assert!(
        files(&cache_dir) == written,
        "the second run changed the cache (names, bytes or modification times of {names:?})"
    );
    assert_eq!(first_film, second_film);
}

/// How a test damages a cache file.
type Damage = fn(&[u8]) -> Vec<u8>;

/// The file with "another adapter" in its key: whole and with a valid checksum, but not
/// this adapter's.
fn foreign(bytes: &[u8]) -> Vec<u8> {
    let key_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let key = std::str::from_utf8(&bytes[HEADER_LEN..HEADER_LEN + key_len]).unwrap();
    assert!(key.contains("adapter: "), "{key}");
    let other = key.replace("adapter: ", "adapter: another GPU ");
    encode(&other, &bytes[HEADER_LEN + key_len..])
}

const DAMAGES: [(&str, Damage); 4] = [
    ("truncated", |b| b[..b.len() / 2].to_vec()),
    ("last byte flipped", |b| {
        let mut b = b.to_vec();
        *b.last_mut().unwrap() ^= 0x5a;
        b
    }),
    ("header byte flipped", |b| {
        let mut b = b.to_vec();
        b[HEADER_LEN - 1] ^= 0x01;
        b
    }),
    ("another adapter's", foreign),
];

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn a_damaged_or_foreign_file_is_ignored_and_replaced() {
    let Some((uncached, _)) = run(|_| DiskCache::off()) else {
        return;
    };
    let dir = temp_dir("disk-cache-damage");
    let cache_dir = dir.join("glint");
    run(|info| DiskCache::at(&cache_dir, info)).unwrap();
    let good = files(&cache_dir);
    for (what, damage) in DAMAGES {
        for (name, (bytes, _)) in &good {
            std::fs::write(cache_dir.join(name), damage(bytes)).unwrap();
        }
        let damaged = files(&cache_dir);
        let (film, info) = run(|info| DiskCache::at(&cache_dir, info)).unwrap();
        assert_eq!(
            (info.compile.rejected, info.compile.reused),
            (PIPELINES, 0),
            "{what}: {:?}",
            info.compile
        );
        assert!(
            film == uncached,
            "{what}: the image differs from the uncached render"
        );
        let now = files(&cache_dir);
        assert_eq!(now.len(), good.len(), "{what}: {:?}", now.keys());
        for (name, (bytes, _)) in &now {
            assert!(bytes != &damaged[name].0, "{what}: {name} was not replaced");
        }
        // The replacement is whole and valid: the next run uses it.
        let (_, next) = run(|info| DiskCache::at(&cache_dir, info)).unwrap();
        assert_eq!(next.compile.reused, PIPELINES, "{what}: {:?}", next.compile);
    }
}

/// Threads that compile the same kernels into one folder at once, as concurrent
/// processes would: every file left is whole and valid, and no temporary file stays.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn concurrent_runs_leave_valid_files() {
    let dir = temp_dir("disk-cache-threads");
    let cache_dir = dir.join("glint");
    let films: Vec<Option<Vec<u32>>> = std::thread::scope(|s| {
        let runs: Vec<_> = (0..3)
            .map(|_| s.spawn(|| run(|info| DiskCache::at(&cache_dir, info)).map(|r| r.0)))
            .collect();
        runs.into_iter().map(|r| r.join().unwrap()).collect()
    });
    let films: Vec<Vec<u32>> = films.into_iter().flatten().collect();
    if films.is_empty() {
        return;
    }
    assert!(films.windows(2).all(|w| w[0] == w[1]));
    let names: Vec<String> = files(&cache_dir).into_keys().collect();
    assert_eq!(names.len(), PIPELINES as usize, "{names:?}");
    assert!(names.iter().all(|n| n.ends_with(".bin")), "{names:?}");
    let (_, next) = run(|info| DiskCache::at(&cache_dir, info)).unwrap();
    assert_eq!(next.compile.reused, PIPELINES, "{:?}", next.compile);
}
