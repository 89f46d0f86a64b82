//! `SceneFeatures`: which capabilities a packed scene uses. The GPU tracer compiles only
//! these in; the CPU tracer skips the same work (Cycles' `KERNEL_FEATURE_*` is the model).

use std::fmt;

/// A set of scene features (bit flags).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct SceneFeatures(pub u32);

impl SceneFeatures {
    pub const SPHERE: SceneFeatures = SceneFeatures(1 << 0);
    pub const CUBE: SceneFeatures = SceneFeatures(1 << 1);
    pub const MESH: SceneFeatures = SceneFeatures(1 << 2);
    pub const REFLECTION: SceneFeatures = SceneFeatures(1 << 3);
    pub const GRID: SceneFeatures = SceneFeatures(1 << 4);
    pub const CYLINDER: SceneFeatures = SceneFeatures(1 << 5);
    pub const CONE: SceneFeatures = SceneFeatures(1 << 6);
    pub const TORUS: SceneFeatures = SceneFeatures(1 << 7);
    pub const AREA_LIGHT: SceneFeatures = SceneFeatures(1 << 8);
    pub const CSG: SceneFeatures = SceneFeatures(1 << 9);
    pub const REFRACTION: SceneFeatures = SceneFeatures(1 << 10);
    pub const TEXTURE: SceneFeatures = SceneFeatures(1 << 11);
    pub const BUMP: SceneFeatures = SceneFeatures(1 << 12);
    /// A mesh triangle with vertex normals (and `shading` not `'flat'`): smooth shading.
    pub const SMOOTH: SceneFeatures = SceneFeatures(1 << 13);

    /// Every feature with its name, in display order.
    pub const ALL: &'static [(SceneFeatures, &'static str)] = &[
        (Self::SPHERE, "sphere"),
        (Self::CUBE, "cube"),
        (Self::MESH, "mesh"),
        (Self::REFLECTION, "reflection"),
        (Self::GRID, "grid"),
        (Self::CYLINDER, "cylinder"),
        (Self::CONE, "cone"),
        (Self::TORUS, "torus"),
        (Self::AREA_LIGHT, "area-light"),
        (Self::CSG, "csg"),
        (Self::REFRACTION, "refraction"),
        (Self::TEXTURE, "texture"),
        (Self::BUMP, "bump"),
        (Self::SMOOTH, "smooth"),
    ];

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
