//! The register budgets over combinations of features, not only over the scenes of
//! `scenes/`: every render kernel of each of `glint kernels --feature-combinations`'s
//! feature sets (src/pack/combinations.rs: every feature, every feature but one, a
//! user's scene that broke them, a strength-3 covering array) compiled on RADV's null
//! device for NAVI21 in wave64 and wave32. The rows over the budgets must be exactly
//! [`KNOWN_BREAKS`] (docs/gpu-kernels.md, "Register budgets"): a new one fails, naming
//! the combination and the kernel, and so does a listed one that no longer breaks.

use crate::kernel_instrument::{glint, number, string, text};
use glint::pack::combinations;
use glint::pack::SceneFeatures;

/// The rows known to break the budgets, each (combination, entry, wave, what breaks):
/// the modules with a mesh, CSG and a grid together, whose closest-hit traversal holds
/// 112 VGPRs in wave32 (a traversal kernel's budget is 96). A combination is `all`, `all
/// but NAMES` or the names of its features.
const KNOWN_BREAKS: &[(&str, &str, u32, &str)] = &[
    ("all", "wavefront_closest", 32, VGPRS_112),
    ("all", "wavefront_leg_closest", 64, "2 spilled SGPRs"),
    ("all", "wavefront_leg_closest", 32, VGPRS_112),
    ("all but sphere", "wavefront_closest", 32, VGPRS_112),
    (
        "all but sphere",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    ("all but sphere", "wavefront_leg_closest", 32, VGPRS_112),
    ("all but cube", "wavefront_closest", 32, VGPRS_112),
    (
        "all but cube",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    ("all but cube", "wavefront_leg_closest", 32, VGPRS_112),
    ("all but reflection", "wavefront_closest", 32, VGPRS_112),
    (
        "all but reflection",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    ("all but reflection", "wavefront_leg_closest", 32, VGPRS_112),
    ("all but cylinder", "wavefront_closest", 32, VGPRS_112),
    (
        "all but cylinder",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    ("all but cylinder", "wavefront_leg_closest", 32, VGPRS_112),
    (
        "all but cone",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    ("all but torus", "wavefront_closest", 32, VGPRS_112),
    ("all but torus", "wavefront_leg_closest", 32, VGPRS_112),
    ("all but area-light", "wavefront_closest", 32, VGPRS_112),
    (
        "all but area-light",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    ("all but area-light", "wavefront_leg_closest", 32, VGPRS_112),
    ("all but refraction", "wavefront_closest", 32, VGPRS_112),
    (
        "all but refraction",
        "wavefront_shadow",
        64,
        "6 spilled SGPRs",
    ),
    ("all but texture", "wavefront_closest", 32, VGPRS_112),
    (
        "all but texture",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    ("all but texture", "wavefront_leg_closest", 32, VGPRS_112),
    ("all but bump", "wavefront_closest", 32, VGPRS_112),
    (
        "all but bump",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    ("all but bump", "wavefront_leg_closest", 32, VGPRS_112),
    ("all but smooth", "wavefront_closest", 32, VGPRS_112),
    (
        "all but smooth",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    ("all but smooth", "wavefront_leg_closest", 32, VGPRS_112),
    ("all but procedural", "wavefront_closest", 32, VGPRS_112),
    (
        "all but procedural",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    ("all but procedural", "wavefront_leg_closest", 32, VGPRS_112),
    // Every feature but depth of field: the set "all" was before the thin lens, breaking
    // as "all" does (the lens adds no row).
    ("all but depth-of-field", "wavefront_closest", 32, VGPRS_112),
    (
        "all but depth-of-field",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    (
        "all but depth-of-field",
        "wavefront_leg_closest",
        32,
        VGPRS_112,
    ),
    ("all but environment", "wavefront_closest", 32, VGPRS_112),
    (
        "all but environment",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
    (
        "all but environment",
        "wavefront_leg_closest",
        32,
        VGPRS_112,
    ),
    // A set of the covering array over 17 features (not in the ones over 14 or 15): a
    // mesh, CSG, a grid and a cone, as every other break; none of the three newest
    // features (depth of field, environment, procedural) is in it.
    (
        "mesh reflection grid cylinder cone area-light csg smooth",
        "wavefront_closest",
        32,
        VGPRS_112,
    ),
    (
        "sphere cube mesh grid cylinder torus csg refraction",
        "wavefront_leg_closest",
        64,
        "2 spilled SGPRs",
    ),
];

const VGPRS_112: &str = "112 VGPRs > 96 (traversal kernel, wave32)";

/// A [`KNOWN_BREAKS`] combination as the instrument names it.
fn combination(spec: &str) -> String {
    let every = SceneFeatures::ALL
        .iter()
        .map(|(_, n)| *n)
        .collect::<Vec<_>>();
    let names = match spec.strip_prefix("all") {
        Some(rest) => {
            let left: Vec<&str> = rest
                .trim()
                .trim_start_matches("but")
                .split_whitespace()
                .collect();
            every
                .iter()
                .filter(|n| !left.contains(n))
                .copied()
                .collect::<Vec<_>>()
                .join(" ")
        }
        None => spec.to_string(),
    };
    combinations::name(combinations::parse(&names).expect("a known combination"))
}

/// One budget row: (combination, entry, wave, what breaks, "; "-joined).
type BreakRow = (String, String, u64, String);

/// The JSON rows of `stdout` that break a budget.
fn breaking_rows(stdout: &str) -> Vec<BreakRow> {
    let mut out = Vec::new();
    for line in stdout.lines().filter(|l| l.contains("\"entry\"")) {
        let breaks = line.split("\"budget_breaks\": [").nth(1).unwrap_or("]");
        let breaks = breaks.trim_end_matches([']', '}', ',']);
        if breaks.is_empty() {
            continue;
        }
        let what: Vec<&str> = breaks
            .split("\", \"")
            .map(|b| b.trim_matches('"'))
            .collect();
        out.push((
            string(line, "scene").unwrap_or("?").to_string(),
            string(line, "entry").unwrap_or("?").to_string(),
            number(line, "wave").unwrap_or(0),
            what.join("; "),
        ));
    }
    out
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn every_kernel_of_every_feature_combination_meets_the_navi21_budgets_but_the_known() {
    let out = glint(&[
        "kernels",
        "--feature-combinations",
        "--format",
        "json",
        "--family",
        "NAVI21",
        "--wave",
        "64",
        "--wave",
        "32",
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    // Every combination compiled, each with rows in both wave sizes.
    for set in combinations::feature_combinations() {
        let scene = format!("\"scene\": \"{}\"", combinations::name(set));
        for wave in [32, 64] {
            let wave = format!("\"wave\": {wave},");
            assert!(
                stdout
                    .lines()
                    .any(|l| l.contains(&scene) && l.contains(&wave)),
                "no {wave} row of {scene}"
            );
        }
    }
    assert!(
        !stdout.contains("\"error\""),
        "every kernel compiles: {stdout}"
    );
    let found = breaking_rows(&stdout);
    let known: Vec<BreakRow> = KNOWN_BREAKS
        .iter()
        .map(|(spec, entry, wave, what)| {
            (
                combination(spec),
                entry.to_string(),
                u64::from(*wave),
                what.to_string(),
            )
        })
        .collect();
    let new: Vec<&BreakRow> = found.iter().filter(|r| !known.contains(r)).collect();
    let gone: Vec<&BreakRow> = known.iter().filter(|r| !found.contains(r)).collect();
    assert!(
        new.is_empty() && gone.is_empty(),
        "kernels over the register budgets (combination, entry, wave, breaks):\n{new:#?}\nknown \
         breaks that no longer break (take them off KNOWN_BREAKS and docs/gpu-kernels.md):\n{gone:#?}"
    );
}
