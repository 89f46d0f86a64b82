//! `glint kernels`: what a real GPU compiler makes of the GPU tracer's kernels. The
//! kernels a render of each scene would create ([`collect`]) are compiled on a Vulkan
//! device below wgpu ([`vulkan`]) — RADV's null device pretending to be an AMD family
//! (`--family NAVI21`), or a hardware device — and each kernel's registers, spills,
//! scratch and code size are read back through `VK_KHR_pipeline_executable_properties`,
//! with the waves per SIMD they leave by the hardware rule ([`occupancy`]) and the
//! register budgets they break ([`budget`]). docs/gpu-kernels.md#the-kernel-instrument.

pub mod budget;
pub mod collect;
pub mod occupancy;
pub mod report;
pub mod stats;
pub mod vulkan;
pub mod wgsl_bounds;

use collect::KernelSet;
use glint::pack::combinations;
use glint::pack::SceneFeatures;
use occupancy::Family;
use stats::KernelStats;
use std::path::{Path, PathBuf};

/// A requested wave size: the driver's default or a required subgroup size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wave {
    Default,
    Required(u32),
}

impl Wave {
    /// `default`, `64` or `32`.
    pub fn parse(s: &str) -> Result<Wave, String> {
        match s {
            "default" => Ok(Wave::Default),
            "64" => Ok(Wave::Required(64)),
            "32" => Ok(Wave::Required(32)),
            _ => Err(format!("wave must be 64, 32 or default, got '{s}'")),
        }
    }
}

/// One kernel compiled at one wave size.
#[derive(Clone, Debug)]
pub struct Compiled {
    /// Index into [`KernelSet::kernels`].
    pub kernel: usize,
    pub wave: Wave,
    /// The figures, or why this device could not compile it at this size.
    pub stats: Result<KernelStats, String>,
}

/// Everything `glint kernels` measured.
pub struct Measurement {
    pub device: String,
    pub family: Option<Family>,
    pub set: KernelSet,
    pub compiled: Vec<Compiled>,
}

/// The environment that makes the Vulkan loader see RADV alone, as a null device of
/// `family`, with Mesa's shader cache off (every figure from a fresh compile). It must
/// be in the environment before the loader loads a driver: the `glint` binary sets it
/// first thing, tests pass it to the child process.
pub fn driver_env(family: Family) -> Result<Vec<(&'static str, String)>, String> {
    let dirs = [
        "/usr/share/vulkan/icd.d",
        "/usr/local/share/vulkan/icd.d",
        "/etc/vulkan/icd.d",
    ];
    let icd = dirs.iter().find_map(|d| {
        let read = std::fs::read_dir(d).ok()?;
        read.flatten().map(|e| e.path()).find(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("radeon_icd"))
        })
    });
    let icd = icd.ok_or_else(|| {
        format!(
            "RADV is not installed (no radeon_icd*.json in {}); Debian: apt-get install mesa-vulkan-drivers",
            dirs.join(", ")
        )
    })?;
    let icd = icd.to_string_lossy().into_owned();
    Ok(vec![
        ("RADV_FORCE_FAMILY", family.name.to_string()),
        ("VK_DRIVER_FILES", icd.clone()),
        ("VK_ICD_FILENAMES", icd),
        ("MESA_SHADER_CACHE_DISABLE", "true".to_string()),
        ("NODEVICE_SELECT", "1".to_string()),
    ])
}

/// Collects the kernels of `scenes` and of the feature sets `combinations` (no script:
/// [`combinations`]), then takes the `own` modules' kernels (compiled already by
/// [`own_modules`], so that a module naga refuses is a bad argument found before any
/// device opens), and compiles each at every size of
/// `waves` on the device (RADV's null device when `family` is set: its [`driver_env`]
/// must be in the environment already).
pub fn measure(
    scenes: &[PathBuf],
    combinations: &[SceneFeatures],
    own: KernelSet,
    family: Option<Family>,
    waves: &[Wave],
    entries: Option<&[glint::gpu::compile::shader::Entry]>,
    variant: glint::gpu::KernelVariant,
) -> Result<Measurement, String> {
    let device = vulkan::StatsDevice::open(family.is_some()).map_err(|e| e.to_string())?;
    let target = glint::gpu::compile::spirv::SpirvTarget::vulkan_1_3();
    let config = collect::variant_config(variant);
    let mut set = KernelSet::default();
    for scene in scenes {
        set.add_scene(scene, entries, config, target)?;
    }
    for &features in combinations {
        let name = combinations::name(features);
        set.add_features(&name, features, entries, config, target)?;
    }
    // Last, and never merged with a scene's kernel of the same entry and features.
    set.kernels.extend(own.kernels);
    let mut compiled = Vec::new();
    for (index, k) in set.kernels.iter().enumerate() {
        for &wave in waves {
            // A device with one subgroup size (GCN: 64) lets none be required: its
            // default is that size.
            let only = device.subgroup_sizes.is_empty();
            let wave = match wave {
                Wave::Required(size) if only && size == device.default_subgroup_size => {
                    Wave::Default
                }
                other => other,
            };
            let stats = match wave {
                Wave::Required(size) if !device.subgroup_sizes.contains(&size) => Err(format!(
                    "the device cannot run wave{size} (sizes: {:?}, default {})",
                    device.subgroup_sizes, device.default_subgroup_size
                )),
                Wave::Required(size) => device
                    .compile(&k.spirv, k.entry, k.kernel, Some(size))
                    .map_err(|e| e.to_string()),
                Wave::Default => device
                    .compile(&k.spirv, k.entry, k.kernel, None)
                    .map_err(|e| e.to_string()),
            };
            compiled.push(Compiled {
                kernel: index,
                wave,
                stats,
            });
        }
    }
    Ok(Measurement {
        device: device.name.clone(),
        family,
        set,
        compiled,
    })
}

/// The kernels of `--wgsl` modules of one's own: each read as every file glint reads,
/// held to [`wgsl_bounds`] and compiled to SPIR-V (parsed and validated by naga) for
/// `entries` of `variant`; an error names the file (and naga's line and column).
pub fn own_modules(
    wgsl: &[PathBuf],
    entries: Option<&[glint::gpu::compile::shader::Entry]>,
    variant: glint::gpu::KernelVariant,
) -> Result<KernelSet, String> {
    let target = glint::gpu::compile::spirv::SpirvTarget::vulkan_1_3();
    let config = collect::variant_config(variant);
    let mut own = KernelSet::default();
    for file in wgsl {
        own.add_wgsl(file, entries, config, target)?;
    }
    Ok(own)
}

/// Writes each distinct kernel as `ENTRY-DIGEST8.spv` and `.wgsl` under `dir` (what
/// `--spirv-dir` asks for, to feed other tools).
pub fn write_kernels(set: &KernelSet, dir: &Path) -> Result<(), String> {
    use std::io::Write;
    glint::atomic_write::create_dir_all_clearly(dir)
        .map_err(|e| format!("{}: {e}", glint::display_path::shown(dir)))?;
    // Each file whole or not at all, through an exclusive temporary file.
    let write = |path: &Path, bytes: &[u8]| {
        glint::atomic_write::write_via_temp(path, |file| file.write_all(bytes))
            .map_err(|e| format!("{}: {e}", glint::display_path::shown(path)))
    };
    for k in &set.kernels {
        let stem = format!("{}-{}", k.entry.name(), &k.digest[..8]);
        let spirv = glint::gpu::compile::spirv::spirv_bytes(&k.spirv);
        write(&dir.join(format!("{stem}.spv")), &spirv)?;
        write(&dir.join(format!("{stem}.wgsl")), k.wgsl.as_bytes())?;
    }
    Ok(())
}
