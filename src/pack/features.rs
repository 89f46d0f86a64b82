//! `SceneFeatures`: which capabilities a packed scene uses. The GPU tracer compiles only
//! these in; the CPU tracer skips the same work (Cycles' `KERNEL_FEATURE_*` is the model).

use std::fmt;

/// A set of scene features (bit flags).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct SceneFeatures(pub u32);

/// The features' flags (`SceneFeatures::NAME`, bit n) and [`SceneFeatures::ALL`], their
/// names in display order (bit order), from one line a feature.
macro_rules! scene_features {
    ($($(#[$doc:meta])* $flag:ident = $bit:literal, $name:literal;)*) => {
        impl SceneFeatures {
            $($(#[$doc])* pub const $flag: SceneFeatures = SceneFeatures(1 << $bit);)*

            /// Every feature with its name, in display order.
            pub const ALL: &'static [(SceneFeatures, &'static str)] = &[$((Self::$flag, $name)),*];
        }
    };
}

scene_features! {
    SPHERE = 0, "sphere";
    CUBE = 1, "cube";
    MESH = 2, "mesh";
    REFLECTION = 3, "reflection";
    GRID = 4, "grid";
    CYLINDER = 5, "cylinder";
    CONE = 6, "cone";
    TORUS = 7, "torus";
    AREA_LIGHT = 8, "area-light";
    CSG = 9, "csg";
    REFRACTION = 10, "refraction";
    TEXTURE = 11, "texture";
    BUMP = 12, "bump";
    /// A mesh triangle with vertex normals (and `shading` not `'flat'`): smooth shading.
    SMOOTH = 13, "smooth";
    /// A thin-lens camera (`aperture` > 0): depth of field.
    DEPTH_OF_FIELD = 14, "depth-of-field";
    /// An HDR environment map (render option `environment`) in place of the background.
    ENVIRONMENT = 15, "environment";
    /// A used material with a procedural texture (`gr.checker`, `gr.noise`, `gr.marble`,
    /// `gr.wood`); it brings TEXTURE (a colour slot) or BUMP (the bump slot) with it, for
    /// the ray cone and the texels it reads.
    PROCEDURAL = 16, "procedural";
}

impl SceneFeatures {
    pub const fn empty() -> SceneFeatures {
        SceneFeatures(0)
    }

    pub const fn contains(self, other: SceneFeatures) -> bool {
        self.0 & other.0 == other.0
    }

    pub fn insert(&mut self, other: SceneFeatures) {
        self.0 |= other.0;
    }

    /// Whether the scene reads textures (TEXTURE or BUMP): what packs triangle UVs and
    /// texels, and gives each hit a texture footprint (the shaders' `#if TEXTURE|BUMP`).
    pub const fn uses_textures(self) -> bool {
        self.contains(Self::TEXTURE) || self.contains(Self::BUMP)
    }
}

impl fmt::Display for SceneFeatures {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = Self::ALL
            .iter()
            .filter(|(flag, _)| self.contains(*flag))
            .map(|(_, name)| *name)
            .collect();
        if names.is_empty() {
            write!(f, "(none)")
        } else {
            write!(f, "{}", names.join(" "))
        }
    }
}
