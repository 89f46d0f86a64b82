//! Procedural textures as the scene language makes them (`gr.checker`, `gr.noise`,
//! `gr.marble`, `gr.wood`), and what a material's texture slot holds: an image or one of
//! them. Evaluated by `tracer::shading::procedural`; packed by `pack::procedural`.

use super::texture::TextureId;

/// The pattern of a procedural texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProceduralKind {
    /// c1 where ⌊x/size⌋ + ⌊y/size⌋ + ⌊z/size⌋ is even, c2 where odd.
    Checker,
    /// fBm of Perlin's improved noise at the point × scale, mapped to [0, 1].
    Noise,
    /// Veins across object x: ½ + ½·sin(π·(x·scale + turbulence·fBm)).
    Marble,
    /// Rings around object z: the fraction of (√(x² + y²)·scale + turbulence·fBm).
    Wood,
}

/// A procedural texture: a pattern t ∈ [0, 1] blending `c1` (t = 0) to `c2` (t = 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Procedural {
    pub kind: ProceduralKind,
    pub c1: [f32; 3],
    pub c2: [f32; 3],
    /// The checker's cube side; the others' frequency (the point is multiplied by it).
    pub scale: f32,
    /// Octaves of the fBm (1 for the checker, which has none).
    pub octaves: u32,
    /// Marble's and wood's turbulence: how far the noise bends the veins or rings (0 for
    /// the checker and noise).
    pub turbulence: f32,
}

/// What a material's texture slot (`set_diffuse`, `set_specular`, `set_bump`) holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TextureRef {
    /// An image of [`SceneGraph::textures`](super::SceneGraph::textures).
    Image(TextureId),
    Procedural(Procedural),
}
