//! `glint kernels SCENE...`: the kernel instrument's command line ([`crate::kernels`]).
//! With `--family` the Vulkan loader is pointed at RADV's null device of that family
//! before anything loads a driver ([`set_driver_env`]); without it, a hardware device
//! that reports compiler statistics is used.

use crate::kernels::occupancy::Family;
use crate::kernels::{collect, measure, report, write_kernels, Wave};
use clap::{Args, ValueEnum};
use glint::gpu::compile::shader::{all_feature_sets, Entry};
use glint::gpu::KernelVariant;
use glint::pack::combinations;
use glint::pack::SceneFeatures;
use std::path::PathBuf;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum KernelsFormat {
    Table,
    Json,
}

/// `glint kernels`' arguments.
#[derive(Args, Debug)]
pub struct KernelsArgs {
    /// Scene scripts; a folder stands for every scene script under it.
    #[arg(required_unless_present_any = ["wgsl", "features", "feature_combinations"])]
    pub scenes: Vec<PathBuf>,
    /// A scene that is only a feature set (repeatable): names such as "mesh torus csg
    /// refraction" (as `render --stats` names them after `features:`; `none` for none), its kernels compiled
    /// as a scene with exactly those features would compile them.
    #[arg(long, value_name = "NAMES", value_parser = combinations::parse)]
    pub features: Vec<SceneFeatures>,
    /// Every feature combination of the budget test (src/pack/combinations.rs).
    #[arg(long)]
    pub feature_combinations: bool,
    /// A WGSL module of one's own (repeatable): its `main` (or --entry) entry points,
    /// laid out as the render module's, beside the scenes' kernels.
    #[arg(long, value_name = "FILE")]
    pub wgsl: Vec<PathBuf>,
    /// Compile on RADV's null device for this AMD family (NAVI21, NAVI10, VEGA10, …);
    /// default: a hardware device that reports compiler statistics.
    #[arg(long, value_parser = Family::parse)]
    pub family: Option<Family>,
    /// Wave size: 64, 32 (a required subgroup size) or default (the driver's choice,
    /// as wgpu leaves it); repeatable. Default: 64 and 32.
    #[arg(long = "wave", value_parser = Wave::parse)]
    pub waves: Vec<Wave>,
    /// Only this entry point (repeatable; one the variant's render modules have: the
    /// hardware variant's have no `main`); default: every entry of the render module.
    #[arg(long = "entry", value_parser = parse_entry)]
    pub entries: Vec<Entry>,
    /// table (markdown) or json.
    #[arg(long, value_enum, default_value = "table")]
    pub format: KernelsFormat,
    /// The kernel variant: hardware (default) or software, as glint chooses by adapter.
    #[arg(long, value_parser = KernelVariant::parse, default_value = "hardware")]
    pub kernel_variant: KernelVariant,
    /// Also write each distinct kernel as ENTRY-HASH.spv and .wgsl into DIR.
    #[arg(long, value_name = "DIR")]
    pub spirv_dir: Option<PathBuf>,
    /// Exit with code 7 and a table of what breaks which budget when a kernel spills,
    /// uses scratch or has too many wave32 VGPRs (docs/gpu-kernels.md#register-budgets).
    #[arg(long)]
    pub check_budget: bool,
}

fn parse_entry(name: &str) -> Result<Entry, String> {
    let render = Entry::ALL.into_iter().filter(|e| e.is_render());
    render.clone().find(|e| e.name() == name).ok_or_else(|| {
        let names: Vec<&str> = render.map(|e| e.name()).collect();
        format!(
            "unknown entry point '{name}' (entries: {})",
            names.join(", ")
        )
    })
}

/// The variant's name as `--kernel-variant` spells it.
fn variant_name(variant: KernelVariant) -> &'static str {
    match variant {
        KernelVariant::Hardware => "hardware",
        KernelVariant::Software => "software",
    }
}

/// An error for the first `--entry` that no render module of the chosen kernel variant has
/// for any feature set (the hardware variant has no megakernel `main`: the wavefront
/// kernels replace it), naming the variant that has it: without it, asking for `main`
/// would silently measure nothing. Not with `--wgsl`, whose own modules may have it.
fn entry_missing_from_variant(args: &KernelsArgs) -> Option<String> {
    if !args.wgsl.is_empty() {
        return None;
    }
    let in_variant = |entry: Entry, variant: KernelVariant| {
        let kernel = collect::variant_config(variant);
        all_feature_sets()
            .into_iter()
            .any(|features| entry.exists_in(kernel, features))
    };
    let chosen = args.kernel_variant;
    let other = match chosen {
        KernelVariant::Hardware => KernelVariant::Software,
        KernelVariant::Software => KernelVariant::Hardware,
    };
    let entry = args
        .entries
        .iter()
        .copied()
        .find(|&entry| !in_variant(entry, chosen))?;
    let hint = if in_variant(entry, other) {
        format!(" (--kernel-variant {} compiles it)", variant_name(other))
    } else {
        String::new()
    };
    Some(format!(
        "entry point '{}' is in no render module of the {} kernel variant{hint}",
        entry.name(),
        variant_name(chosen)
    ))
}

/// Points the Vulkan loader at RADV's null device of `args.family`, if given.
///
/// # Safety
/// Changes the process environment: call it while no other thread runs and before any
/// Vulkan loader is loaded (the `glint` binary calls it right after parsing).
pub unsafe fn set_driver_env(args: &KernelsArgs) -> Result<(), String> {
    if let Some(family) = args.family {
        for (name, value) in crate::kernels::driver_env(family)? {
            // SAFETY: the caller's contract above.
            unsafe { std::env::set_var(name, value) };
        }
    }
    Ok(())
}

/// Runs the instrument and prints its table or JSON on stdout. Exit codes: 2 bad
/// arguments (a scene folder without scenes, an `--entry` the variant lacks), 5 no
/// Vulkan, RADV or device, 7 a budget broken with `--check-budget`.
pub fn run_kernels(args: &KernelsArgs) -> Result<(), (String, u8)> {
    let mut scenes = Vec::new();
    for s in &args.scenes {
        if s.is_dir() {
            let found = collect::scenes_under(s);
            if found.is_empty() {
                return Err((
                    format!(
                        "{}: no scene scripts under it",
                        glint::display_path::shown(s)
                    ),
                    2,
                ));
            }
            scenes.extend(found);
        } else {
            scenes.push(s.clone());
        }
    }
    if let Some(message) = entry_missing_from_variant(args) {
        return Err((message, 2));
    }
    let entries = (!args.entries.is_empty()).then_some(args.entries.as_slice());
    // A module of one's own that cannot be read, or that naga refuses (a syntax or a
    // validation error), is a bad argument, found before any device is opened.
    let own = crate::kernels::own_modules(&args.wgsl, entries, args.kernel_variant)
        .map_err(|e| (e, 2))?;
    let waves = if args.waves.is_empty() {
        vec![Wave::Required(64), Wave::Required(32)]
    } else {
        args.waves.clone()
    };
    let mut features = args.features.clone();
    if args.feature_combinations {
        features.extend(combinations::feature_combinations());
    }
    let m = measure(
        &scenes,
        &features,
        own,
        args.family,
        &waves,
        entries,
        args.kernel_variant,
    )
    .map_err(|e| (e, 5))?;
    if let Some(dir) = &args.spirv_dir {
        write_kernels(&m.set, dir).map_err(|e| (e, 4))?;
    }
    match args.format {
        KernelsFormat::Table => print!("{}", report::table(&m)),
        KernelsFormat::Json => print!("{}", report::json(&m)),
    }
    let failed: Vec<String> = m
        .compiled
        .iter()
        .filter_map(|c| c.stats.as_ref().err().cloned())
        .collect();
    if args.check_budget {
        let breaks = report::budget_report(&m);
        if !breaks.is_empty() || !failed.is_empty() {
            // The whole table on stderr: the error line itself is capped at a few KiB.
            eprint!("{breaks}");
            for f in &failed {
                eprintln!("not compiled: {f}");
            }
            let rows = breaks.lines().count().saturating_sub(2);
            return Err((
                format!(
                    "{rows} kernel rows break the register budgets and {} did not compile (the table above; the budgets: docs/gpu-kernels.md#register-budgets)",
                    failed.len()
                ),
                7,
            ));
        }
    }
    Ok(())
}
