//! Render options: the optional 11th argument of `gr.render`, overridable by CLI flags of
//! the same name. One struct with the documented defaults (yocto-gl style).

/// Anti-aliasing mode (`aa`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AaMode {
    /// One ray through each pixel centre.
    None,
    /// n×n jittered samples per pixel (`samples`).
    Uniform,
    /// Corner samples, subdivided where neighbours differ.
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

#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    pub aa: AaMode,
    pub samples: u32,
    pub aa_threshold: f32,
    pub aa_depth: u32,
    pub shadow_samples: Option<u32>,
    pub max_depth: u32,
    pub min_weight: f32,
    pub background: Background,
    pub grid: GridMode,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            aa: AaMode::Adaptive,
            samples: 4,
            aa_threshold: 0.1,
            aa_depth: 3,
            shadow_samples: None,
            max_depth: 8,
            min_weight: 1.0 / 512.0,
            background: Background::DEFAULT,
            grid: GridMode::Auto,
        }
    }
}
