//! The wavefront's queues are specified once (`src/tracer/wavefront/queues.rs`): the CPU's structures
//! of arrays and the WGSL accessors both come from that table, so neither side can have
//! a queue field the other lacks. This test (no GPU) checks that both sides do use it:
//! - every render module with the wavefront kernels holds the generated accessors, and
//!   naga sees a getter and a setter for every field of every region of its layout;
//! - the CPU's batch holds the generated structures, their fields the specification's;
//! - no hand-written queue field on either side: no WGSL of the wavefront indexes the
//!   `samples` buffer's queues itself (only the lattice, by `lattice_index`), and no
//!   struct of the CPU wavefront has a `Vec` field of its own ([`queue_problems`]).

use super::twins::source_texts;
use glint::gpu::compile::shader::{
    all_feature_sets, assemble_with, queue_accessors, validate, Entry,
};
use glint::gpu::KernelConfig;
use glint::pack::SceneFeatures;
use glint::tracer::wavefront::queues::counters::counters_wgsl;
use glint::tracer::wavefront::queues::layout::{in_layout, Form};
use glint::tracer::wavefront::queues::wgsl::queue_wgsl;
use glint::tracer::wavefront::queues::{LegQueue, COUNTERS, REGIONS};
use glint::tracer::wavefront::wavefront::Batch;
use std::collections::BTreeSet;

/// Every function the generator may emit (either layout, every field, the counters).
pub(super) fn generated_functions() -> BTreeSet<String> {
    [Form::Chain, Form::Tree]
        .iter()
        .flat_map(|&form| {
            let text = queue_wgsl(REGIONS, form, &|_| true) + &counters_wgsl(COUNTERS, form);
            text.lines()
                .filter_map(|l| l.strip_prefix("fn "))
                .filter_map(|l| l.split_once('(').map(|(name, _)| name.to_string()))
                .collect::<Vec<_>>()
        })
        .collect()
}

/// The file name of a repository path (the layout may move files between folders).
fn file_name(path: &str) -> &str {
    path.rsplit('/').next().unwrap_or(path)
}

/// Hand-written queue fields or accesses in `texts` (repository path, text): a line of
/// the wavefront's WGSL that indexes `samples` other than at a lattice point, and a `Vec`
/// field of a struct in the CPU wavefront's files (a queue field outside the
/// specification).
pub(super) fn queue_problems(texts: &[(String, String)]) -> Vec<String> {
    let mut problems = Vec::new();
    for (path, text) in texts {
        let name = file_name(path);
        let in_wavefront = path.starts_with("src/tracer/wavefront/");
        let wgsl = name.ends_with(".wgsl") && (in_wavefront || name == "progressive.wgsl");
        let rust = in_wavefront && name.ends_with(".rs");
        for (number, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or_default().trim();
            if wgsl && code.contains("samples[") && !code.contains("samples[lattice_index(") {
                problems.push(format!(
                    "{path}:{}: reads or writes the queues by hand; add the field to \
                     src/tracer/wavefront/queues.rs and use its generated accessors: {code}",
                    number + 1
                ));
            }
            let field = code
                .trim_start_matches("pub ")
                .trim_start_matches("pub(crate) ");
            if rust
                && code.ends_with(',')
                && field
                    .split_once(": Vec<")
                    .is_some_and(|(n, _)| n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
            {
                problems.push(format!(
                    "{path}:{}: a queue field outside src/tracer/wavefront/queues.rs (the GPU has no \
                     lanes for it): {code}",
                    number + 1
                ));
            }
        }
    }
    problems
}

/// The repository's sources have no hand-written queue field or access.
#[test]
fn queues_are_read_and_written_through_the_specification() {
    let problems = queue_problems(&source_texts());
    assert!(problems.is_empty(), "{problems:#?}");
}

/// Each render module with the wavefront kernels (every feature set, both layouts) holds
/// the generated accessors, and naga sees each field's getter and setter in it.
#[test]
fn modules_hold_the_generated_accessors() {
    let kernel = KernelConfig {
        wavefront: true,
        ..KernelConfig::default()
    };
    for features in all_feature_sets() {
        let source = assemble_with(features, Entry::Render, kernel);
        assert!(
            source.contains(&queue_accessors(features, kernel)),
            "{features}"
        );
        let module = validate(&source, features).unwrap();
        let names: BTreeSet<&str> = module
            .functions
            .iter()
            .filter_map(|(_, f)| f.name.as_deref())
            .collect();
        let form = if features.contains(SceneFeatures::REFRACTION) {
            Form::Tree
        } else {
            Form::Chain
        };
        for region in REGIONS.iter().filter(|r| r.in_form(form)) {
            for field in region.record.fields.iter().filter(|f| in_layout(f, form)) {
                if field.condition.is_some_and(|c| c != "REFRACTION") {
                    continue; // present only with its features: see the unit tests
                }
                let getter = format!("{}_{}", region.name, field.name);
                assert!(names.contains(getter.as_str()), "{features}: no {getter}");
                let setter = format!("set_{getter}");
                assert!(names.contains(setter.as_str()), "{features}: no {setter}");
            }
        }
    }
}

/// The CPU's batch and leg queue are the generated structures: each prints (Debug) as
/// the specification's record, field for field.
#[test]
fn the_cpu_holds_the_generated_structures() {
    let printed = format!("{:?} {:?}", Batch::default(), LegQueue::default());
    for region in REGIONS {
        let record = region.record;
        let fields: Vec<String> = record
            .fields
            .iter()
            .map(|f| format!("{}: []", f.name))
            .collect();
        let expected = format!("{} {{ {} }}", record.rust, fields.join(", "));
        assert!(
            printed.contains(&expected),
            "the CPU has no {expected}: {printed}"
        );
    }
}

/// A queue field added by hand on one side is reported: a WGSL accessor that reads a
/// lane of its own, a `Vec` added to the CPU's batch.
#[test]
fn a_field_on_one_side_is_reported() {
    let texts = source_texts();
    let edit = |file: &str, from: &str, to: &str| -> Vec<(String, String)> {
        let mut out = texts.clone();
        let (_, text) = out
            .iter_mut()
            .find(|(f, t)| file_name(f) == file && t.contains(from))
            .unwrap_or_else(|| panic!("no {file} has {from}"));
        *text = text.replacen(from, to, 1);
        out
    };
    let wgsl = edit(
        "batch.wgsl",
        "// Path i of parity `parity` as trace_ray's stack holds it.",
        "fn path_extra(parity: u32, i: u32) -> f32 {\n    return samples[path_queue(parity) + 4u * i + 3u].y;\n}\n\n// Path i of parity `parity` as trace_ray's stack holds it.",
    );
    let problems = queue_problems(&wgsl);
    assert!(
        problems
            .iter()
            .any(|p| p.contains("batch.wgsl") && p.contains("by hand")),
        "a hand-written WGSL accessor is not reported: {problems:?}"
    );
    let rust = edit(
        "batch.rs",
        "    pub light_points: u32,\n",
        "    pub light_points: u32,\n    pub extra: Vec<f32>,\n",
    );
    let problems = queue_problems(&rust);
    assert!(
        problems
            .iter()
            .any(|p| p.contains("batch.rs") && p.contains("pub extra: Vec<f32>,")),
        "a hand-added CPU queue field is not reported: {problems:?}"
    );
}
