//! The render-options table, the optional 11th argument of `gr.render`.
//!
//! Strict on purpose: a misspelt key (`samlpes`) or value (`aa = 'adaptiv'`) is an error
//! that lists what is valid, rather than an option silently left at its default.

use super::args::{describe, finite, int_value, Args};
use crate::scene::{AaMode, Background, Bounded, DebugView, GridMode, RenderOptions, Shading};
use mlua::{Table, Value};

const KEYS: &str = "aa, samples, aa_threshold, aa_depth, shadow_samples, max_depth, \
                    min_weight, background, environment, environment_rotation, grid, debug, \
                    shading, aperture, focus";

/// Parses argument `n` of `a` (nil gives the defaults).
pub(super) fn parse(a: &Args, n: usize) -> mlua::Result<RenderOptions> {
    let mut o = RenderOptions::default();
    let t = match a.get(n) {
        Value::Nil => return Ok(o),
        Value::Table(t) => t.clone(),
        _ => return Err(a.bad(n, "options", "a table of render options")),
    };
    for (key, v) in sorted_entries(a, n, &t)? {
        set_option(a, n, &mut o, &key, &v)?;
    }
    Ok(o)
}

/// Most keys an options table may have (each option once, with room to spare).
const MAX_OPTION_KEYS: usize = 32;

/// The table's entries sorted by key, so that a table with several mistakes always
/// reports the same one first; a key that is not a string is an error.
fn sorted_entries(a: &Args, n: usize, t: &Table) -> mlua::Result<Vec<(String, Value)>> {
    let mut entries: Vec<(String, Value)> = Vec::new();
    for pair in t.pairs::<Value, Value>() {
        let (k, v) = pair?;
        // There are only a few options: a table with more keys has a wrong one, and is
        // not copied whole (it may hold millions).
        if entries.len() >= MAX_OPTION_KEYS {
            return Err(a.bad_in(
                n,
                "options",
                format!("more than {MAX_OPTION_KEYS} keys; options are {KEYS}"),
            ));
        }
        let Value::String(k) = &k else {
            return Err(a.bad_in(
                n,
                "options",
                format!(
                    "keys must be option names ({KEYS}), got {}",
                    describe(a.lua, &k)
                ),
            ));
        };
        entries.push((super::args::lossy_prefix(k, 64), v));
    }
    entries.sort_by(|x, y| x.0.cmp(&y.0));
    Ok(entries)
}

/// Sets the option `key` of `o` to `v`, or says why `v` (or `key`) is not valid.
fn set_option(a: &Args, n: usize, o: &mut RenderOptions, key: &str, v: &Value) -> mlua::Result<()> {
    let bad = |what: &str| {
        a.bad_in(
            n,
            "options",
            format!("{key} must be {what}, got {}", describe(a.lua, v)),
        )
    };
    fn bounded<const MIN: u32, const MAX: u32>(
        v: &Value,
        bad: impl Fn(&str) -> mlua::Error,
    ) -> mlua::Result<Bounded<MIN, MAX>> {
        int_value(v)
            .and_then(Bounded::new)
            .ok_or_else(|| bad(&Bounded::<MIN, MAX>::expected()))
    }
    match key {
        "aa" => {
            o.aa = match v {
                Value::String(s) => AaMode::parse(&super::args::lossy_prefix(s, 64)),
                _ => None,
            }
            .ok_or_else(|| bad(AaMode::CHOICES))?;
        }
        "samples" => o.samples = bounded(v, bad)?,
        "aa_threshold" => {
            o.aa_threshold = match finite(v) {
                Some(x) if x >= 0.0 => x as f32,
                _ => return Err(bad("a non-negative number")),
            }
        }
        "aa_depth" => o.aa_depth = bounded(v, bad)?,
        "shadow_samples" => o.shadow_samples = Some(bounded(v, bad)?),
        "max_depth" => o.max_depth = bounded(v, bad)?,
        "min_weight" => {
            o.min_weight = match finite(v) {
                Some(x) if (0.0..=1.0).contains(&x) => x as f32,
                _ => return Err(bad("a number from 0 to 1")),
            }
        }
        "aperture" => {
            o.aperture = match finite(v) {
                Some(x) if x >= 0.0 && (x as f32).is_finite() => x as f32,
                _ => return Err(bad("a non-negative lens radius (0: pinhole)")),
            }
        }
        "focus" => {
            o.focus = match finite(v) {
                Some(x) if x > 0.0 && (x as f32).is_finite() && x as f32 > 0.0 => Some(x as f32),
                _ => return Err(bad("a positive distance")),
            }
        }
        "background" => o.background = background(a, n, v)?,
        "environment" => o.environment = Some(super::maps::environment(a, n, v)?),
        "environment_rotation" => {
            o.environment_rotation = match finite(v) {
                Some(x) => x as f32,
                None => return Err(bad("a number of degrees")),
            }
        }
        "debug" => {
            o.debug = match v {
                Value::String(s) => DebugView::parse(&super::args::lossy_prefix(s, 64)),
                _ => None,
            }
            .ok_or_else(|| bad(DebugView::CHOICES))?;
        }
        "grid" => o.grid = grid(a, n, v, &bad)?,
        "shading" => {
            o.shading = match v {
                Value::String(s) => Shading::parse(&s.to_string_lossy()),
                _ => None,
            }
            .ok_or_else(|| bad(Shading::CHOICES))?;
        }
        _ => {
            return Err(a.bad_in(
                n,
                "options",
                format!("unknown key '{key}'; valid keys are {KEYS}"),
            ))
        }
    }
    Ok(())
}

/// `'auto'`, `'off'` or `{density = λ}`; any other value is `bad`.
fn grid(
    a: &Args,
    n: usize,
    v: &Value,
    bad: &dyn Fn(&str) -> mlua::Error,
) -> mlua::Result<GridMode> {
    match v {
        Value::String(s) if s.as_bytes().as_ref() == b"auto" => Ok(GridMode::Auto),
        Value::String(s) if s.as_bytes().as_ref() == b"off" => Ok(GridMode::Off),
        Value::Table(t) => {
            let d: Value = t.raw_get("density")?;
            match finite(&d) {
                Some(x) if x > 0.0 => Ok(GridMode::Density(x as f32)),
                _ => Err(a.bad_in(
                    n,
                    "options",
                    format!(
                        "grid.density must be a positive number, got {}",
                        describe(a.lua, &d)
                    ),
                )),
            }
        }
        _ => Err(bad(GridMode::CHOICES)),
    }
}

/// `{r,g,b}` or `{top={r,g,b}, bottom={r,g,b}}`.
fn background(a: &Args, n: usize, v: &Value) -> mlua::Result<Background> {
    const WHAT: &str = "{r, g, b} or {top = {r, g, b}, bottom = {r, g, b}}";
    let Value::Table(t) = v else {
        return Err(a.bad_in(
            n,
            "options",
            format!("background must be {WHAT}, got {}", describe(a.lua, v)),
        ));
    };
    let colour = |t: &Table, what: &str| -> mlua::Result<[f32; 3]> {
        let mut c = [0.0f32; 3];
        for (i, slot) in c.iter_mut().enumerate() {
            let x: Value = t.raw_get(i + 1)?;
            *slot = finite(&x).ok_or_else(|| {
                a.bad_in(
                    n,
                    "options",
                    format!(
                        "{what} element {} must be a finite number, got {}",
                        i + 1,
                        describe(a.lua, &x)
                    ),
                )
            })? as f32;
        }
        Ok(c)
    };
    let top: Value = t.raw_get("top")?;
    let bottom: Value = t.raw_get("bottom")?;
    match (&top, &bottom) {
        (Value::Nil, Value::Nil) => Ok(Background::Solid(colour(t, "background")?)),
        (Value::Table(top), Value::Table(bottom)) => Ok(Background::Gradient {
            top: colour(top, "background.top")?,
            bottom: colour(bottom, "background.bottom")?,
        }),
        _ => Err(a.bad_in(
            n,
            "options",
            format!("background must be {WHAT} (both top and bottom for a gradient)"),
        )),
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::lua::{run_scene_source, ScriptConfig};
    use crate::scene::{AaMode, Background, DebugView, GridMode, RenderOptions, Shading};
    use std::path::Path;

    /// Runs a one-line render with `opts` as the options argument.
    fn options(opts: &str) -> Result<RenderOptions, String> {
        let src = format!(
            "gr.render(gr.node('r'), 'o.png', 8, 8, {{0,0,1}}, {{0,0,-1}}, {{0,1,0}}, 50, \
             {{0,0,0}}, {{}}, {opts})"
        );
        let mut got = None;
        run_scene_source(
            "o.lua",
            &src,
            Path::new("."),
            &ScriptConfig::default(),
            &mut |_, r| {
                got = Some(r.options.clone());
                Ok(())
            },
        )
        .map_err(|e| e.to_string())?;
        Ok(got.unwrap())
    }

    #[test]
    fn nil_gives_defaults() {
        assert_eq!(options("nil").unwrap(), RenderOptions::default());
        assert_eq!(options("{}").unwrap(), RenderOptions::default());
    }

    #[test]
    fn every_key_parses() {
        let o = options(
            "{aa='none', samples=2, aa_threshold=0.25, aa_depth=1, shadow_samples=9, \
             max_depth=3, min_weight=0.01, background={0.1,0.2,0.3}, grid='off'}",
        )
        .unwrap();
        assert_eq!(o.aa, AaMode::None);
        assert_eq!(
            (o.samples.get(), o.aa_depth.get(), o.max_depth.get()),
            (2, 1, 3)
        );
        assert_eq!(o.aa_threshold, 0.25);
        assert_eq!(o.shadow_samples.map(|s| s.get()), Some(9));
        assert_eq!(o.min_weight, 0.01);
        assert_eq!(o.background, Background::Solid([0.1, 0.2, 0.3]));
        assert_eq!(o.grid, GridMode::Off);
        let o = options("{background={top={0,0,1}, bottom={1,1,1}}, grid={density=3}}").unwrap();
        assert_eq!(
            o.background,
            Background::Gradient {
                top: [0.0, 0.0, 1.0],
                bottom: [1.0, 1.0, 1.0]
            }
        );
        assert_eq!(o.grid, GridMode::Density(3.0));
        assert_eq!(options("{shading='flat'}").unwrap().shading, Shading::Flat);
        assert_eq!(options("{}").unwrap().shading, Shading::Smooth);
        let e = options("{shading='phong'}").unwrap_err();
        assert!(
            e.ends_with("shading must be 'smooth' or 'flat', got 'phong'"),
            "{e}"
        );
        let o = options("{aperture=0.5, focus=3}").unwrap();
        assert_eq!((o.aperture, o.focus), (0.5, Some(3.0)));
        assert_eq!(options("{}").unwrap().aperture, 0.0);
        assert_eq!(options("{debug='uv'}").unwrap().debug, DebugView::Uv);
        assert_eq!(
            options("{debug='aa-samples'}").unwrap().debug,
            DebugView::AaSamples
        );
        let e = options("{debug='normals'}").unwrap_err();
        assert!(
            e.ends_with("debug must be 'none', 'uv' or 'aa-samples', got 'normals'"),
            "{e}"
        );
    }

    #[test]
    fn bad_values_list_the_choices() {
        // (options, how the error ends)
        for (opts, end) in [
            (
                "{grid='fast'}",
                "grid must be 'auto', 'off' or {density=λ}, got 'fast'",
            ),
            (
                "{samples=0}",
                "samples must be an integer from 1 to 64, got 0",
            ),
        ] {
            let e = options(opts).unwrap_err();
            assert!(e.ends_with(end), "{opts}: {e}");
        }
        // (options, a part of the error)
        for (opts, part) in [
            ("{min_weight=2}", "min_weight must be a number from 0 to 1"),
            ("{background={top={0,0,1}}}", "both top and bottom"),
            (
                "{grid={density=-1}}",
                "grid.density must be a positive number, got -1",
            ),
            ("{4}", "keys must be option names"),
            (
                "{aperture=-0.1}",
                "aperture must be a non-negative lens radius (0: pinhole), got -0.1",
            ),
            (
                "{aperture=0/0}",
                "aperture must be a non-negative lens radius",
            ),
            (
                "{aperture=1e39}",
                "aperture must be a non-negative lens radius",
            ),
            ("{focus=0}", "focus must be a positive distance, got 0"),
            ("{focus=-2}", "focus must be a positive distance, got -2"),
            ("{focus=1/0}", "focus must be a positive distance"),
            ("{focus='far'}", "focus must be a positive distance"),
        ] {
            let e = options(opts).unwrap_err();
            assert!(e.contains(part), "{opts}: {e}");
        }
        // Not a table: ignored, as the course's binding did (issue 37), with a note.
        assert_eq!(options("'fast'").unwrap(), RenderOptions::default());
    }
}
