//! Evidence that a scene was written for CS488 before Fall 2015, whose transforms
//! right-multiply (`--transform-order post`): the hint at the end of a render names it.
//!
//! Only what the eras do differently counts. Strong on its own: `readobj` (the old
//! course's mesh reader), Lua 5.1's bare `unpack`, an inline mesh built by a `require`d
//! module (the old course shipped meshes as Lua modules; since 2015 they are OBJ files).
//! An inline mesh in the scene itself is no evidence alone (a quad floor is the way to
//! make a plane in any year): with it, a node whose last transform is a rotate or scale
//! after a translate (the old order writes the outermost step first) counts.

use super::with_state;
use crate::scene::NodeId;
use std::collections::BTreeMap;

/// What the script has done that tells the eras apart (kept in the script's state).
#[derive(Debug, Default)]
pub(crate) struct EraEvidence {
    /// The first strong evidence, as words for the hint (`readobj at scene.lua:8`).
    strong: Option<String>,
    /// Where the scene itself first built an inline mesh.
    inline_mesh_at: Option<String>,
    /// Per node transformed: where it was rotated or scaled after a translate, as its
    /// last transform so far (None once a later translate follows).
    after_translate: BTreeMap<NodeId, Option<String>>,
}

/// One transform call on a node, for [`EraEvidence`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TransformKind {
    Translate,
    RotateOrScale,
}

/// Records strong evidence: `what` at the current line (`bare unpack at scene.lua:3`).
pub(crate) fn strong(lua: &mlua::Lua, what: &str) {
    if with_state(lua, |s| s.era.strong.is_some()) {
        return;
    }
    // Located outside `with_state`: finding the line reads the state too.
    let at = super::args::location(lua);
    with_state(lua, |s| s.era.strong = Some(format!("{what} at {at}")));
}

/// Records an inline mesh built at `at` by the scene's own code.
pub(crate) fn inline_mesh(lua: &mlua::Lua, at: String) {
    with_state(lua, |s| {
        s.era.inline_mesh_at.get_or_insert(at);
    });
}

/// Records a transform of `node` by the scene's code (the line is looked up only when
/// it becomes evidence, so a loop of transforms stays cheap).
pub(crate) fn transform(lua: &mlua::Lua, node: NodeId, kind: TransformKind) {
    let wanted = with_state(lua, |s| match kind {
        TransformKind::Translate => {
            s.era.after_translate.insert(node, None);
            false
        }
        TransformKind::RotateOrScale => s
            .era
            .after_translate
            .get(&node)
            .is_some_and(Option::is_none),
    });
    if wanted && super::preludes::caller_module_dir(lua).is_none() {
        let at = super::args::location(lua);
        with_state(lua, |s| s.era.after_translate.insert(node, Some(at)));
    }
}

impl EraEvidence {
    /// The evidence, in words, if the scene looks pre-2015.
    pub fn verdict(&self) -> Option<String> {
        if let Some(strong) = &self.strong {
            return Some(strong.clone());
        }
        let mesh = self.inline_mesh_at.as_ref()?;
        let order = self.after_translate.values().flatten().next()?;
        Some(format!(
            "an inline mesh at {mesh}, and a node rotated or scaled after its translate at {order}"
        ))
    }
}
