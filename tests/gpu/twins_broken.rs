//! The twin checker of `tests/gpu/twins.rs` fails where it should: each test feeds it
//! edited copies of the real sources (a tie, an argument or a call broken) and asserts
//! that the break is reported.

use super::twins::{check, source_texts, Findings};

/// `texts` with the first `from` in `file` replaced by `to`.
fn edited(texts: &[(String, String)], file: &str, from: &str, to: &str) -> Vec<(String, String)> {
    let mut out = texts.to_vec();
    let (_, text) = out.iter_mut().find(|(f, _)| f == file).unwrap();
    assert!(text.contains(from), "{file} has no {from}");
    *text = text.replacen(from, to, 1);
    out
}

/// Each kind of broken tie is reported (the checks can fail).
#[test]
fn broken_ties_are_reported() {
    let texts = source_texts();
    let renamed = check(&edited(
        &texts,
        "src/tracer/geometry/uv.wgsl",
        "fn triangle_frame(",
        "fn triangle_frame_renamed(",
    ));
    assert!(
        renamed
            .problems
            .iter()
            .any(|p| p.contains("src/tracer/geometry/uv.wgsl declares no triangle_frame")),
        "renaming a WGSL twin is not caught: {:?}",
        renamed.problems
    );
    // Its callers now call a function that does not exist: naga says so.
    assert_reported(
        &renamed,
        "the module does not parse",
        "a module naga cannot parse",
    );
    // The caller passes it too, so the module still parses and naga counts it.
    let extra = check(&edited(
        &edited(
            &texts,
            "src/tracer/geometry/uv.wgsl",
            "fn triangle_frame(p0",
            "fn triangle_frame(extra: f32, p0",
        ),
        "src/tracer/shading/surface.wgsl",
        "triangle_frame(p0, p1",
        "triangle_frame(0.0, p0, p1",
    ));
    assert!(
        extra.problems.iter().any(|p| p.contains(
            "triangle_frame passes 7 arguments but its twin src/tracer/geometry/uv.wgsl:"
        )),
        "an extra WGSL parameter is not caught: {:?}",
        extra.problems
    );
    let one_sided = check(&edited(
        &texts,
        "src/tracer/geometry/uv.rs",
        "// Mirror of src/tracer/geometry/uv.wgsl::triangle_frame — change both.\n",
        "",
    ));
    assert!(
        one_sided
            .problems
            .iter()
            .any(|p| p.contains("names src/tracer/geometry/uv.rs::triangle_frame as its twin")),
        "a one-sided twin comment is not caught: {:?}",
        one_sided.problems
    );
    // safe_rcp3's WGSL twin moved to intersect.wgsl, both comments following it.
    let block = "// safe_rcp of each component.\n// Mirror of src/tracer/base/math.rs::safe_rcp3 — change both.\nfn safe_rcp3(v: vec3<f32>) -> vec3<f32> {\n    return vec3<f32>(safe_rcp(v.x), safe_rcp(v.y), safe_rcp(v.z));\n}\n";
    let moved = edited(&texts, "src/tracer/base/math.wgsl", block, "");
    let moved = edited(
        &moved,
        "src/tracer/geometry/intersect.wgsl",
        "// #if SPHERE\n",
        &format!("{block}// #if SPHERE\n"),
    );
    let moved = check(&edited(
        &moved,
        "src/tracer/base/math.rs",
        "Mirror of src/tracer/base/math.wgsl::safe_rcp3",
        "Mirror of src/tracer/geometry/intersect.wgsl::safe_rcp3",
    ));
    assert_reported(
        &moved,
        "safe_rcp3 has its twin in src/tracer/geometry/intersect.wgsl, not in src/tracer/base/math.wgsl",
        "a twin in a file of another name",
    );
    let new_fn = check(&edited(
        &texts,
        "src/tracer/geometry/uv.wgsl",
        "// #if SPHERE\n",
        "fn untwinned() {}\n// #if SPHERE\n",
    ));
    assert!(
        new_fn
            .problems
            .iter()
            .any(|p| p.contains("fn untwinned has no twin comment")),
        "a WGSL function without a twin is not caught: {:?}",
        new_fn.problems
    );
}

/// `problems` has one containing `needle`, else the test fails saying `what` is missed.
fn assert_reported(found: &Findings, needle: &str, what: &str) {
    assert!(
        found.problems.iter().any(|p| p.contains(needle)),
        "{what} is not caught (no problem says \"{needle}\"): {:#?}",
        found.problems
    );
}

/// Each kind of broken call is reported (the call check can fail): a step added on one
/// side only (either side), a call to a different twin, twins called in another order,
/// a Rust twin renamed.
#[test]
fn broken_calls_are_reported() {
    let texts = source_texts();
    let wgsl_only = check(&edited(
        &texts,
        "src/tracer/shading/surface.wgsl",
        "    var m = 0.0;\n",
        "    var m = safe_rcp(1.0);\n",
    ));
    assert_reported(
        &wgsl_only,
        "affine_magnitude calls safe_rcp (twin of src/tracer/base/math.rs::safe_rcp), but its twin src/tracer/shading/surface.rs:",
        "a call added to a WGSL twin only",
    );
    let rust_only = check(&edited(
        &texts,
        "src/tracer/geometry/uv.rs",
        "    let e1 = p[1] - p[0];\n",
        "    let e1 = p[1] - p[0] + super::math::safe_rcp3(normal);\n",
    ));
    assert_reported(
        &rust_only,
        "triangle_frame calls src/tracer/base/math.rs::safe_rcp3 (twin of shaders' safe_rcp3), but its twin src/tracer/geometry/uv.wgsl:",
        "a call added to a Rust twin only",
    );
    let other_twin = check(&edited(
        &texts,
        "src/tracer/geometry/intersect.wgsl",
        "let interval = sphere_interval(o, d);",
        "let interval = box_interval(o, d);",
    ));
    for needle in [
        "intersect_sphere calls box_interval (twin of src/tracer/geometry/intersect.rs::box_interval)",
        "intersect_sphere calls src/tracer/geometry/intersect.rs::sphere_interval (twin of shaders' sphere_interval)",
    ] {
        assert_reported(&other_twin, needle, "a call of another twin");
    }
    let reordered = check(&edited(
        &texts,
        "src/tracer/sampling/adaptive.rs",
        "    let k = lattice_index(&t, i, j);\n    let (colour, hint) = lattice_sample(scene, fx, fy, counters);\n",
        "    let (colour, hint) = lattice_sample(scene, fx, fy, counters);\n    let k = lattice_index(&t, i, j);\n",
    ));
    assert_reported(
        &reordered,
        "trace_lattice_point: twins called in another order: Rust [\"lattice_position\", \"lattice_sample\", \"lattice_index\", \"encode_hint\"], WGSL [\"lattice_position\", \"lattice_index\", \"lattice_sample\", \"encode_hint\"]",
        "twins called in another order",
    );
    let renamed = check(&edited(
        &texts,
        "src/tracer/geometry/uv.rs",
        "pub fn triangle_frame(",
        "pub fn triangle_frame_renamed(",
    ));
    assert_reported(
        &renamed,
        "src/tracer/geometry/uv.rs declares no triangle_frame",
        "a renamed Rust twin",
    );
}

/// Twins named apart are reported: a pair whose Rust side takes another name (both
/// comments following it, so every tie still holds), and a WGSL function whose twin
/// comment names part of a Rust function of another name.
#[test]
fn names_apart_are_reported() {
    let texts = source_texts();
    let renamed = edited(
        &edited(
            &edited(
                &texts,
                "src/tracer/wavefront/wavefront_gather.rs",
                "fn wavefront_gather(",
                "fn gather_entry(",
            ),
            "src/tracer/wavefront/wavefront_gather.rs",
            "    each_path(scene, batch, counters, wavefront_gather);",
            "    each_path(scene, batch, counters, gather_entry);",
        ),
        "src/tracer/wavefront/wavefront_gather.wgsl",
        "src/tracer/wavefront/wavefront_gather.rs::wavefront_gather — change both.",
        "src/tracer/wavefront/wavefront_gather.rs::gather_entry — change both.",
    );
    let found = check(&renamed);
    assert_reported(
        &found,
        "fn wavefront_gather is named otherwise than its twin src/tracer/wavefront/wavefront_gather.rs::gather_entry",
        "a pair of twins named apart",
    );
    assert_eq!(found.problems.len(), 1, "{:#?}", found.problems);
    let partial = edited(
        &edited(
            &edited(
                &texts,
                "src/tracer/sampling/render.rs",
                "// Mirror of src/tracer/sampling/render.wgsl::uniform_resolve — change both.\npub fn uniform_resolve(",
                "pub fn mean_of_samples(",
            ),
            "src/tracer/sampling/render.rs",
            "uniform_resolve(uniform_samples(",
            "mean_of_samples(uniform_samples(",
        ),
        "src/tracer/sampling/render.wgsl",
        "// Mirror of src/tracer/sampling/render.rs::uniform_resolve — change both.",
        "// Mirror of the sum of src/tracer/sampling/render.rs::render_pixel — change both.",
    );
    let found = check(&partial);
    assert_reported(
        &found,
        "fn uniform_resolve has no Rust function of its name",
        "a WGSL function mirroring part of a Rust function of another name",
    );
    assert_eq!(found.problems.len(), 1, "{:#?}", found.problems);
}
