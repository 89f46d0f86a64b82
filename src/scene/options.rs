//! Render options: the optional 11th argument of `gr.render`, overridable by CLI flags of
//! the same name. One struct with the documented defaults (yocto-gl style).

use super::bounded::{AaDepth, AaSamples, ShadowSamples, TraceDepth};

/// Anti-aliasing mode (`aa`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AaMode {
    /// One ray through each pixel centre.
    None,
    /// n×n jittered samples per pixel (`samples`).
    Uniform,
    /// Corner and centre samples, subdivided where they differ.
    Adaptive,
}

impl AaMode {
    pub const CHOICES: &'static str = "'none', 'uniform' or 'adaptive'";

    pub fn parse(s: &str) -> Option<AaMode> {
        match s {
            "none" => Some(AaMode::None),
            "uniform" => Some(AaMode::Uniform),
            "adaptive" => Some(AaMode::Adaptive),
            _ => None,
        }
    }
}

/// Colour of rays that hit nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Background {
    Solid([f32; 3]),
    /// Vertical gradient by ray direction: `bottom` looking straight down (along −up),
    /// `top` looking straight up, linear in between.
    Gradient {
        top: [f32; 3],
        bottom: [f32; 3],
    },
}

impl Background {
    /// glint's default: a pale horizon under a deeper blue zenith.
    pub const DEFAULT: Background = Background::Gradient {
        top: [0.18, 0.30, 0.55],
        bottom: [0.78, 0.82, 0.90],
    };
}

/// Acceleration structure choice (`grid`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GridMode {
    /// Uniform grid with the benchmark-tuned density.
    Auto,
    /// Brute force over every item (kept for comparison).
    Off,
    /// Uniform grid with cells ≈ λ × items.
    Density(f32),
}

impl GridMode {
    pub const CHOICES: &'static str = "'auto', 'off' or {density=λ}";
}

/// Debug view (`debug`, the scene option and `--debug`): what the image shows instead
/// of the shaded render.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum DebugView {
    /// The normal image.
    #[default]
    None,
    /// Colour = (u mod 1, v mod 1, 0) of the surface a primary ray hits first.
    Uv,
    /// Adaptive anti-aliasing's work per pixel (drawn by the `aa_map` module); needs
    /// adaptive AA.
    AaSamples,
}

impl DebugView {
    pub const CHOICES: &'static str = "'none', 'uv' or 'aa-samples'";

    pub fn parse(s: &str) -> Option<DebugView> {
        match s {
            "none" => Some(DebugView::None),
            "uv" => Some(DebugView::Uv),
            "aa-samples" => Some(DebugView::AaSamples),
            _ => None,
        }
    }
}

/// Parses `--debug`'s value.
pub fn parse_debug_view(s: &str) -> Result<DebugView, String> {
    DebugView::parse(s).ok_or_else(|| format!("debug must be {}, got '{s}'", DebugView::CHOICES))
}

/// Mesh shading (`shading`): whether meshes with vertex normals interpolate them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Shading {
    /// Triangles whose corners all have normals shade with the normals interpolated at
    /// the hit (Phong normal interpolation); the rest are flat.
    #[default]
    Smooth,
    /// Every triangle shades with its geometric normal; vertex normals are ignored.
    Flat,
}

impl Shading {
    pub const CHOICES: &'static str = "'smooth' or 'flat'";

    pub fn parse(s: &str) -> Option<Shading> {
        match s {
            "smooth" => Some(Shading::Smooth),
            "flat" => Some(Shading::Flat),
            _ => None,
        }
    }
}

/// Parses `--shading`'s value.
pub fn parse_shading(s: &str) -> Result<Shading, String> {
    Shading::parse(s).ok_or_else(|| format!("shading must be {}, got '{s}'", Shading::CHOICES))
}

#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    pub aa: AaMode,
    pub samples: AaSamples,
    pub aa_threshold: f32,
    pub aa_depth: AaDepth,
    pub shadow_samples: Option<ShadowSamples>,
    pub max_depth: TraceDepth,
    pub min_weight: f32,
    pub background: Background,
    pub grid: GridMode,
    pub debug: DebugView,
    pub shading: Shading,
    /// Thin-lens radius in scene units (`aperture`); 0 is the pinhole camera.
    pub aperture: f32,
    /// Distance from the eye, along the view direction, of the plane in focus (`focus`);
    /// `None` is the length of `gr.render`'s view vector (the distance to the point it
    /// looks at when given as that point minus the eye).
    pub focus: Option<f32>,
    /// The HDR environment map rays that escape see instead of the background.
    pub environment: Option<std::sync::Arc<super::environment::Environment>>,
    /// The environment map's turn about +y, in degrees (counter-clockwise seen from +y).
    pub environment_rotation: f32,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            aa: AaMode::Adaptive,
            samples: AaSamples::constant(4),
            // The sampling defaults are chosen by `glint bench --sweep`'s stated rule
            // (docs/performance.md#sampling-settings-error-against-time).
            aa_threshold: 0.2,
            aa_depth: AaDepth::constant(3),
            shadow_samples: None,
            max_depth: TraceDepth::constant(8),
            min_weight: 1.0 / 512.0,
            background: Background::DEFAULT,
            grid: GridMode::Auto,
            debug: DebugView::None,
            shading: Shading::Smooth,
            aperture: 0.0,
            focus: None,
            environment: None,
            environment_rotation: 0.0,
        }
    }
}

/// Option values given outside the script (CLI flags); each `Some` beats the scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OptionOverrides {
    pub aa: Option<AaMode>,
    pub samples: Option<AaSamples>,
    pub aa_threshold: Option<f32>,
    pub aa_depth: Option<AaDepth>,
    pub shadow_samples: Option<ShadowSamples>,
    pub max_depth: Option<TraceDepth>,
    pub min_weight: Option<f32>,
    pub background: Option<Background>,
    pub grid: Option<GridMode>,
    pub debug: Option<DebugView>,
    pub shading: Option<Shading>,
    pub aperture: Option<f32>,
    pub focus: Option<f32>,
    pub width: Option<u32>,
    pub height: Option<u32>,
}

impl OptionOverrides {
    /// Applies every given value to `options`.
    pub fn apply(&self, options: &mut RenderOptions) {
        fn set<T: Clone>(target: &mut T, value: &Option<T>) {
            if let Some(v) = value {
                *target = v.clone();
            }
        }
        set(&mut options.aa, &self.aa);
        set(&mut options.samples, &self.samples);
        set(&mut options.aa_threshold, &self.aa_threshold);
        set(&mut options.aa_depth, &self.aa_depth);
        if self.shadow_samples.is_some() {
            options.shadow_samples = self.shadow_samples;
        }
        set(&mut options.max_depth, &self.max_depth);
        set(&mut options.min_weight, &self.min_weight);
        set(&mut options.background, &self.background);
        set(&mut options.grid, &self.grid);
        set(&mut options.debug, &self.debug);
        set(&mut options.shading, &self.shading);
        set(&mut options.aperture, &self.aperture);
        if self.focus.is_some() {
            options.focus = self.focus;
        }
    }
}

/// Parses `--aperture`'s value: a lens radius, finite and not negative.
pub fn parse_aperture(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!(
            "aperture must be a non-negative lens radius (0: pinhole), got '{s}'"
        )),
    }
}

/// Parses `--focus`'s value: a distance, finite and positive.
pub fn parse_focus(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("focus must be a positive distance, got '{s}'")),
    }
}

/// Parses `auto`, `off` or a density λ (`4`, `density=4`) as a grid mode.
pub fn parse_grid_mode(s: &str) -> Result<GridMode, String> {
    match s {
        "auto" => Ok(GridMode::Auto),
        "off" => Ok(GridMode::Off),
        _ => {
            let number = s.strip_prefix("density=").unwrap_or(s);
            match number.parse::<f32>() {
                Ok(d) if d.is_finite() && d > 0.0 => Ok(GridMode::Density(d)),
                _ => Err(format!(
                    "grid must be 'auto', 'off' or a positive density λ (e.g. 'density=4'), got '{s}'"
                )),
            }
        }
    }
}

/// Parses `r,g,b` (a solid colour) or `r,g,b/r,g,b` (top/bottom gradient).
pub fn parse_background(s: &str) -> Result<Background, String> {
    let colour = |part: &str| -> Result<[f32; 3], String> {
        let values: Vec<f32> = part
            .split(',')
            .map(|v| v.trim().parse::<f32>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("background colour '{part}' must be three numbers r,g,b"))?;
        match values[..] {
            [r, g, b] if values.iter().all(|v| v.is_finite()) => Ok([r, g, b]),
            _ => Err(format!(
                "background colour '{part}' must be three numbers r,g,b"
            )),
        }
    };
    match s.split_once('/') {
        Some((top, bottom)) => Ok(Background::Gradient {
            top: colour(top)?,
            bottom: colour(bottom)?,
        }),
        None => Ok(Background::Solid(colour(s)?)),
    }
}
