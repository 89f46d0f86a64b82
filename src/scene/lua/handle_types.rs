//! The userdata types the `gr` calls return, apart from their methods (in `handles`):
//! argument checking (`args`) recognises them without depending on the methods, which
//! themselves read their arguments through `args`.

use crate::scene::{Light, NodeId};

/// A node made by `gr.node`, `gr.sphere`, … (index into `SceneGraph::nodes`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct NodeHandle(pub NodeId);

/// A material made by `gr.material` (index into `SceneGraph::materials`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct MaterialHandle(pub usize);

/// A light made by `gr.light`; lights live in `gr.render`'s list, not in the graph.
#[derive(Clone, Debug)]
pub(crate) struct LightHandle(pub Light);

/// A procedural texture made by `gr.checker`, `gr.noise`, `gr.marble` or `gr.wood`: a
/// value, accepted wherever a texture file name is (`set_diffuse`, `set_specular`,
/// `set_bump`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ProceduralHandle(pub crate::scene::Procedural);

impl ProceduralHandle {
    /// What a procedural texture prints as and is described as in errors.
    pub(crate) fn describe(&self) -> String {
        use crate::scene::ProceduralKind;
        let name = match self.0.kind {
            ProceduralKind::Checker => "gr.checker",
            ProceduralKind::Noise => "gr.noise",
            ProceduralKind::Marble => "gr.marble",
            ProceduralKind::Wood => "gr.wood",
        };
        format!("a procedural texture ({name})")
    }
}
