//! The WGSL accessors of the wavefront's queues, generated from the specification (`tracer::wavefront::queues`)
//! and [`super::layout`] into the render module (after the constants' prelude, in modules
//! with the wavefront kernels), so no `.wgsl` file repeats the layout. Per region R
//! (`path`, `hit`, …; arguments `points` where its place depends on the light points,
//! `parity` where it has two copies, then the entry's index `i`):
//! - `R_queue(…)`: where the region starts in `samples`, `R_STRIDE` its entries' vec4s;
//! - per field F: `R_F(…, i)` reads it, `set_R_F(…, i, value)` writes it (one lane, or
//!   its vec4s with their other lanes kept), `set_R_F_component(…, i, c, value)` one
//!   component of a vector;
//! - `set_R_F_G(…, i, f, g)`: a vec4 that holds whole fields F, G, … written at once;
//! - `write_R(…, i, fields…)`: the whole entry, a vec4 a store, unused lanes zero (a
//!   field the module lacks is still an argument, `F_unused`, its lanes zero); `R_entry(…, i)` where
//!   entry i starts and `write_R_at(at, fields…)` the same write there;
//! - `load_R(…, i)`: the entry as the record's WGSL struct, where it has one (`Hit`);
//! - `path_capacity()`: the paths a generation may hold.

use super::layout::{in_layout, lanes, stride, Extent, Form, Region};
use super::QueueField;

/// A WGSL type a field may have: its components (whether each is a u32, stored bit-cast)
/// as a value's parts, and how a value is built from them where a constructor over the
/// parts in order (a scalar: its one part) does not do.
struct WgslType {
    name: &'static str,
    parts: &'static [(&'static str, bool)],
    custom_build: Option<fn(&[String]) -> String>,
}

impl WgslType {
    /// A type whose value is its constructor over its parts (a scalar: its one part).
    const fn plain(name: &'static str, parts: &'static [(&'static str, bool)]) -> WgslType {
        WgslType {
            name,
            parts,
            custom_build: None,
        }
    }

    /// The expression building a value from its parts' expressions.
    fn build(&self, parts: &[String]) -> String {
        match (self.custom_build, parts) {
            (Some(build), _) => build(parts),
            (None, [scalar]) => scalar.clone(),
            (None, _) => format!("{}({})", self.name, parts.join(", ")),
        }
    }
}

const TYPES: &[WgslType] = &[
    WgslType::plain("f32", &[("", false)]),
    WgslType::plain("u32", &[("", true)]),
    WgslType::plain("vec2<f32>", &[(".x", false), (".y", false)]),
    WgslType::plain("vec3<f32>", &[(".x", false), (".y", false), (".z", false)]),
    WgslType::plain("vec2<u32>", &[(".x", true), (".y", true)]),
    WgslType {
        name: "MediumStack",
        parts: &[
            (".iors[0]", false),
            (".iors[1]", false),
            (".iors[2]", false),
            (".iors[3]", false),
            (".count", true),
        ],
        custom_build: Some(|c| {
            format!(
                "MediumStack(array<f32, MEDIUM_STACK_SIZE>({}), {})",
                c[..4].join(", "),
                c[4]
            )
        }),
    },
];

/// The WGSL type named `name`. Panics on one the generator does not know (a bug in the
/// specification, which the unit tests read whole).
fn wgsl_type(name: &str) -> &'static WgslType {
    TYPES
        .iter()
        .find(|t| t.name == name)
        .unwrap_or_else(|| panic!("queue field type {name} has no WGSL encoding"))
}

/// Whether a field is a float vector whose components lie in order in one vec4 (read
/// and written as a swizzle of it).
fn swizzled(field: &QueueField) -> Option<(u32, String)> {
    let ty = wgsl_type(field.wgsl);
    let lanes = lanes(field);
    let one_word = lanes.iter().all(|&(w, _)| w == lanes[0].0);
    let in_order = lanes.windows(2).all(|p| p[1].1 == p[0].1 + 1);
    let floats = ty.parts.iter().all(|&(_, u)| !u);
    (lanes.len() > 1 && one_word && in_order && floats && ty.name.starts_with("vec")).then(|| {
        let swizzle: String = lanes
            .iter()
            .map(|&(_, c)| "xyzw".as_bytes()[c] as char)
            .collect();
        (lanes[0].0, swizzle)
    })
}

/// `samples[at + w]`.
fn word(w: u32) -> String {
    if w == 0 {
        "samples[at]".to_string()
    } else {
        format!("samples[at + {w}u]")
    }
}

/// A lane read as its component's type.
fn read_lane(w: u32, lane: usize, uint: bool) -> String {
    let lane = format!("{}.{}", word(w), "xyzw".as_bytes()[lane] as char);
    if uint {
        format!("bitcast<u32>({lane})")
    } else {
        lane
    }
}

/// The expression reading `field`.
fn read_field(field: &QueueField) -> String {
    if let Some((w, swizzle)) = swizzled(field) {
        return format!("{}.{swizzle}", word(w));
    }
    let ty = wgsl_type(field.wgsl);
    let parts: Vec<String> = lanes(field)
        .iter()
        .zip(ty.parts)
        .map(|(&(w, lane), &(_, uint))| read_lane(w, lane, uint))
        .collect();
    ty.build(&parts)
}

/// The vec4 `w` with `value`'s lanes of `field`s set and its other lanes `other(lane)`;
/// consecutive float-vector lanes of one field as the vector.
fn word_value(w: u32, fields: &[(&QueueField, String)], other: impl Fn(usize) -> String) -> String {
    let mut items = Vec::new();
    let mut lane = 0;
    while lane < 4 {
        let owner = fields.iter().find_map(|(f, value)| {
            lanes(f)
                .iter()
                .position(|&l| l == (w, lane))
                .map(|part| (*f, value, part))
        });
        match owner {
            Some((f, value, _)) if swizzled(f).is_some_and(|(sw, _)| sw == w) => {
                items.push(value.clone());
                lane += lanes(f).len();
            }
            Some((f, value, part)) => {
                let (suffix, uint) = wgsl_type(f.wgsl).parts[part];
                let component = format!("{value}{suffix}");
                items.push(if uint {
                    format!("bitcast<f32>({component})")
                } else {
                    component
                });
                lane += 1;
            }
            None => {
                items.push(other(lane));
                lane += 1;
            }
        }
    }
    format!("vec4<f32>({})", items.join(", "))
}

/// The WGSL of an extent: multiples of the chunk's samples, of the paths a generation
/// may hold, of the tree's vertices and of the light points of those paths.
fn extent_wgsl(e: Extent, form: Form) -> String {
    let (samples, paths) = match form {
        Form::Chain => (e.samples + e.paths, 0),
        Form::Tree => (e.samples, e.paths),
    };
    let light_points_unit = match form {
        Form::Chain => "points * tile.items",
        Form::Tree => "points * path_capacity()",
    };
    let terms: Vec<String> = [
        (samples, "tile.items"),
        (paths, "path_capacity()"),
        (e.tree_vertices, "TREE_VERTICES_PER_SAMPLE * tile.items"),
        (e.light_points, light_points_unit),
    ]
    .iter()
    .filter(|(n, _)| *n > 0)
    .map(|(n, unit)| format!("{n}u * {unit}"))
    .collect();
    if terms.is_empty() {
        "0u".to_string()
    } else {
        terms.join(" + ")
    }
}

/// A region's accessors' leading parameters (declared, and as passed on).
fn region_params(
    region: &Region,
    regions: &[Region],
    form: Form,
) -> (Vec<&'static str>, Vec<&'static str>) {
    let offset = region.offset(regions, form);
    let copy = region.copy_size(form);
    let mut params = Vec::new();
    let mut names = Vec::new();
    if offset.light_points > 0 || (region.copies > 1 && copy.light_points > 0) {
        params.push("points: u32");
        names.push("points");
    }
    if region.copies > 1 {
        params.push("parity: u32");
        names.push("parity");
    }
    (params, names)
}

/// The accessors of one region in `form`'s layout, with the fields `present` keeps.
fn region_wgsl(
    region: &Region,
    regions: &[Region],
    form: Form,
    present: &dyn Fn(&str) -> bool,
) -> String {
    let name = region.name;
    let (params, names) = region_params(region, regions, form);
    let mut base = extent_wgsl(region.offset(regions, form), form);
    if region.copies > 1 {
        let copy = extent_wgsl(region.copy_size(form), form);
        base = format!("{base} + {copy} * parity");
    }
    let s = stride(&region.record, form);
    let mut out = format!(
        "const {}_STRIDE: u32 = {s}u;\nfn {name}_queue({}) -> u32 {{\n    return {base};\n}}\n",
        name.to_uppercase(),
        params.join(", ")
    );
    let head = [params.clone(), vec!["i: u32"]].concat().join(", ");
    let call = names.join(", ");
    let at = if s == 1 {
        format!("    let at = {name}_queue({call}) + i;\n")
    } else {
        format!("    let at = {name}_queue({call}) + {s}u * i;\n")
    };
    let layout: Vec<&QueueField> = region
        .record
        .fields
        .iter()
        .filter(|f| in_layout(f, form))
        .collect();
    let fields: Vec<&QueueField> = layout
        .iter()
        .copied()
        .filter(|f| f.condition.is_none_or(present))
        .collect();
    for f in &fields {
        out += &field_wgsl(name, f, &head, &at);
    }
    out += &word_setters(name, &fields, &head, &at);
    let values: Vec<(&QueueField, String)> =
        fields.iter().map(|f| (*f, f.name.to_string())).collect();
    // Every field of the layout is an argument; one the module lacks (its `#if`) leaves
    // its lanes zero, and a vec4 only such fields take is not written.
    let args: Vec<String> = layout
        .iter()
        .map(|f| {
            let unused = if fields.contains(f) { "" } else { "_unused" };
            format!("{}{unused}: {}", f.name, f.wgsl)
        })
        .collect();
    out += &format!("fn write_{name}({head}, {})", args.join(", "));
    out += " {\n";
    out += &at;
    out += &store_words(&values, false);
    out += "}\n";
    // The same, at an entry's place found beforehand (`R_entry`): a kernel that finds it
    // before a traversal keeps one index live across it (wavefront_leg_closest).
    let at_expr = at
        .trim()
        .trim_start_matches("let at = ")
        .trim_end_matches(';');
    out += &format!("fn {name}_entry({head}) -> u32 {{\n    return {at_expr};\n}}\n");
    out += &format!("fn write_{name}_at(at: u32, {})", args.join(", "));
    out += " {\n";
    out += &store_words(&values, false);
    out += "}\n";
    if let Some(ty) = region.record.wgsl_struct {
        let parts: Vec<String> = fields.iter().map(|f| read_field(f)).collect();
        out += &format!(
            "fn load_{name}({head}) -> {ty} {{\n{at}    return {ty}({});\n}}\n",
            parts.join(", ")
        );
    }
    out
}

/// Stores of the vec4s `values`' fields touch, in vec4 order; where `keep`, a lane no
/// field of them takes keeps its value, else it is zero.
fn store_words(values: &[(&QueueField, String)], keep: bool) -> String {
    let mut words: Vec<u32> = values
        .iter()
        .flat_map(|(f, _)| lanes(f).into_iter().map(|(w, _)| w))
        .collect();
    words.sort_unstable();
    words.dedup();
    let mut out = String::new();
    for w in words {
        let mine: Vec<(u32, usize)> = values
            .iter()
            .flat_map(|(f, _)| lanes(f))
            .filter(|&(lw, _)| lw == w)
            .collect();
        if keep && mine.len() == 1 {
            let (f, value) = values
                .iter()
                .find(|(f, _)| lanes(f).contains(&mine[0]))
                .unwrap();
            let part = lanes(f).iter().position(|&l| l == mine[0]).unwrap();
            let (suffix, uint) = wgsl_type(f.wgsl).parts[part];
            let component = format!("{value}{suffix}");
            let component = if uint {
                format!("bitcast<f32>({component})")
            } else {
                component
            };
            out += &format!(
                "    {}.{} = {component};\n",
                word(w),
                "xyzw".as_bytes()[mine[0].1] as char
            );
            continue;
        }
        let other = |lane: usize| {
            if keep {
                format!("{}.{}", word(w), "xyzw".as_bytes()[lane] as char)
            } else {
                "0.0".to_string()
            }
        };
        out += &format!("    {} = {};\n", word(w), word_value(w, values, other));
    }
    out
}

/// A field's getter, setter and (vectors) component setter.
fn field_wgsl(region: &str, f: &QueueField, head: &str, at: &str) -> String {
    let (name, ty) = (f.name, f.wgsl);
    let mut out = format!(
        "fn {region}_{name}({head}) -> {ty} {{\n{at}    return {};\n}}\n",
        read_field(f)
    );
    out += &format!("fn set_{region}_{name}({head}, value: {ty})");
    out += " {\n";
    out += at;
    out += &store_words(&[(f, "value".to_string())], true);
    out += "}\n";
    if let Some(scalar) = ty.strip_prefix("vec").and_then(|t| t.get(1..)) {
        let scalar = scalar.trim_start_matches('<').trim_end_matches('>');
        out += &format!("fn set_{region}_{name}_component({head}, c: u32, value: {scalar})");
        out += " {\n";
        out += at;
        let lanes = lanes(f);
        let uint = scalar == "u32";
        for (c, &(w, lane)) in lanes.iter().enumerate() {
            let value = if uint { "bitcast<f32>(value)" } else { "value" };
            let store = format!("{}.{} = {value};", word(w), "xyzw".as_bytes()[lane] as char);
            let test = if c == 0 {
                "    if c == 0u {\n".to_string()
            } else if c + 1 < lanes.len() {
                format!(" else if c == {c}u") + " {\n"
            } else {
                " else {\n".to_string()
            };
            out += &format!("{test}        {store}");
            out += "\n    }";
        }
        out += "\n}\n";
    }
    out
}

/// For each vec4 that holds two or more whole fields and nothing else: a setter of them
/// together (one store).
fn word_setters(region: &str, fields: &[&QueueField], head: &str, at: &str) -> String {
    let mut out = String::new();
    let mut words: Vec<u32> = fields
        .iter()
        .flat_map(|f| lanes(f))
        .map(|(w, _)| w)
        .collect();
    words.sort_unstable();
    words.dedup();
    for w in words {
        let touching: Vec<&QueueField> = fields
            .iter()
            .copied()
            .filter(|f| lanes(f).iter().any(|&(lw, _)| lw == w))
            .collect();
        let whole = touching
            .iter()
            .all(|f| lanes(f).iter().all(|&(lw, _)| lw == w));
        if touching.len() < 2 || !whole {
            continue;
        }
        let names: Vec<&str> = touching.iter().map(|f| f.name).collect();
        let args: Vec<String> = touching
            .iter()
            .map(|f| format!("{}: {}", f.name, f.wgsl))
            .collect();
        let values: Vec<(&QueueField, String)> =
            touching.iter().map(|f| (*f, f.name.to_string())).collect();
        out += &format!(
            "fn set_{region}_{}({head}, {})",
            names.join("_"),
            args.join(", ")
        );
        out += " {\n";
        out += at;
        out += &store_words(&values, false);
        out += "}\n";
    }
    out
}

/// The accessors of the queues of `regions` (`tracer::wavefront::queues::REGIONS`) in a render module with the wavefront kernels in `form`'s layout;
/// `present` says whether the module has a field's `#if` condition.
pub fn queue_wgsl(regions: &[Region], form: Form, present: &dyn Fn(&str) -> bool) -> String {
    let capacity = match form {
        Form::Chain => "tile.items",
        Form::Tree => "TREE_PATHS_PER_SAMPLE * tile.items",
    };
    let mut out = format!(
        "// The wavefront's queue accessors, generated from src/tracer/wavefront/queues.rs ({form:?} layout).\n\
         fn path_capacity() -> u32 {{\n    return {capacity};\n}}\n"
    );
    for region in regions.iter().filter(|r| r.in_form(form)) {
        out += &region_wgsl(region, regions, form, present);
    }
    out
}
