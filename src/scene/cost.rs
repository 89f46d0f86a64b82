//! What a render will cost, counted from the scene graph before anything is built.
//!
//! Instancing makes a DAG: a node under two parents is flattened twice, so a graph of 40
//! nodes whose instances double at each level flattens into 2⁴⁰ objects. The counts here
//! come from the DAG's path counts (one memoised pass over the nodes reachable from the
//! root), so a render is refused before flattening starts when it would not fit the
//! memory budget. The byte figures are upper estimates of what flattening, packing, the
//! grid and the film hold per item (with the slack of growing vectors).

use super::flat::{FlattenError, MAX_NODE_DEPTH};
use super::{NodeId, NodeKind, Primitive, SceneGraph};
use crate::constants::CSG_MAX_DEPTH;

/// Bytes per flattened analytic object: `Object` (with its transform), its packed
/// instance, its grid bounds and cell references, doubled for vector growth.
pub const OBJECT_BYTES: u64 = 768;
/// Bytes per flattened triangle while it is packed (the graph's mesh, already charged
/// when it was read, is shared with the flattened scene, not copied): the packed triangle
/// (36), its UVs (24) and normals (36) when the scene uses them, the packing order (4), its
/// bounds while the grid is made (24), the grid's cells (λ = 2 per triangle, 4 bytes each)
/// and references (3 per triangle at 12 bytes while sorted) — 176 — with room for
/// allocator blocks and large triangles' extra references. Measured: 81 (2×10⁶-triangle
/// bumpy torus) and 97 (10⁶ random triangles) bytes per triangle over the mesh
/// (docs/performance-trace.md, "Loading big meshes").
pub const TRIANGLE_BYTES: u64 = 256;
/// Bytes per image pixel: the f32 film, the 8-bit copy written out, and adaptive
/// anti-aliasing's per-pixel bookkeeping.
pub const PIXEL_BYTES: u64 = 32;
/// Bytes per texel of the packed texture copy the tracers read.
pub const TEXEL_BYTES: u64 = 4;
/// Most node visits one flattening may make (paths from the root through the DAG,
/// including transform nodes that hold no geometry): a bound on its time.
pub const MAX_PATHS: u64 = 1 << 26;

/// The counts of one render's scene, from [`scene_cost`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneCost {
    /// Node visits flattening makes (root-to-node paths).
    pub paths: u64,
    /// Analytic objects, CSG leaves included.
    pub objects: u64,
    pub triangles: u64,
    /// Bytes of the objects' path names (`root/arm/hand`).
    pub name_bytes: u64,
}

impl SceneCost {
    /// Estimated bytes to flatten, pack and grid the scene (not the film).
    pub fn bytes(&self) -> u64 {
        self.objects
            .saturating_mul(OBJECT_BYTES)
            .saturating_add(self.triangles.saturating_mul(TRIANGLE_BYTES))
            .saturating_add(self.name_bytes)
    }
}

/// Per node: its counts and the height of the DAG below it (for the depth limit).
#[derive(Clone, Copy)]
struct Memo {
    cost: SceneCost,
    height: usize,
}

/// Counts what flattening the graph below `root` would make. Errors when a path is
/// deeper than [`MAX_NODE_DEPTH`] (as flattening would).
pub fn scene_cost(graph: &SceneGraph, root: NodeId) -> Result<SceneCost, FlattenError> {
    let mut memo: Vec<Option<Memo>> = vec![None; graph.nodes.len()];
    let mut csg_memo: Vec<Option<CsgMemo>> = vec![None; graph.nodes.len()];
    let mut path = Vec::new();
    count(graph, root, &mut memo, &mut csg_memo, &mut path).map(|m| m.cost)
}

fn count(
    graph: &SceneGraph,
    id: NodeId,
    memo: &mut [Option<Memo>],
    csg_memo: &mut [Option<CsgMemo>],
    path: &mut Vec<NodeId>,
) -> Result<Memo, FlattenError> {
    path.push(id);
    let too_deep = || FlattenError::TooDeep {
        path: path
            .iter()
            .map(|&n| super::short_name(&graph.nodes[n].name))
            .collect::<Vec<_>>()
            .join("/"),
    };
    if let Some(m) = memo[id] {
        if path.len() + m.height > MAX_NODE_DEPTH + 1 {
            return Err(too_deep());
        }
        path.pop();
        return Ok(m);
    }
    if path.len() > MAX_NODE_DEPTH {
        return Err(too_deep());
    }
    let node = &graph.nodes[id];
    let name_len = node.name.len() as u64;
    let mut cost = SceneCost {
        paths: 1,
        ..SceneCost::default()
    };
    match node.kind {
        NodeKind::Geometry {
            primitive: Primitive::Mesh(mesh),
            ..
        } => {
            cost.triangles = graph
                .meshes
                .get(mesh)
                .map_or(0, |m| m.triangles.len() as u64);
        }
        NodeKind::Geometry { .. } => {
            cost.objects = 1;
            cost.name_bytes = name_len;
        }
        NodeKind::Csg { .. } => {
            let info = csg_info(graph, id, csg_memo);
            // A tree nested too deep is refused by flattening; it builds nothing.
            let leaves = if info.height <= CSG_MAX_DEPTH {
                info.leaves
            } else {
                0
            };
            cost.objects = leaves;
            // Each leaf is named by the CSG node's path and its own below it.
            cost.name_bytes = leaves.saturating_mul(name_len.saturating_add(64));
        }
        NodeKind::Transform => {}
    }
    let mut height = 1;
    for &child in &node.children {
        let c = count(graph, child, memo, csg_memo, path)?;
        height = height.max(c.height + 1);
        cost.paths = cost.paths.saturating_add(c.cost.paths);
        cost.objects = cost.objects.saturating_add(c.cost.objects);
        cost.triangles = cost.triangles.saturating_add(c.cost.triangles);
        // Every object below gets this node's name and a separator in its path.
        cost.name_bytes = cost
            .name_bytes
            .saturating_add(c.cost.name_bytes)
            .saturating_add(c.cost.objects.saturating_mul(name_len + 1));
    }
    let m = Memo { cost, height };
    memo[id] = Some(m);
    path.pop();
    Ok(m)
}

/// A CSG subtree's leaves (paths through its operand DAG to a primitive) and height
/// (CSG levels; a primitive is 0).
#[derive(Clone, Copy)]
struct CsgMemo {
    leaves: u64,
    height: u32,
}

/// Counts the CSG tree at `id` from its operand DAG, each node once (memoised across
/// the whole count, without recursion: a shared tree of 10⁶ CSG nodes costs 10⁶ steps,
/// not one per path).
fn csg_info(graph: &SceneGraph, id: NodeId, memo: &mut [Option<CsgMemo>]) -> CsgMemo {
    let mut stack = vec![id];
    while let Some(&top) = stack.last() {
        if memo[top].is_some() {
            stack.pop();
            continue;
        }
        match graph.nodes[top].kind {
            NodeKind::Csg { a, b, .. } => match (memo[a], memo[b]) {
                (Some(ma), Some(mb)) => {
                    memo[top] = Some(CsgMemo {
                        leaves: ma.leaves.saturating_add(mb.leaves),
                        height: 1 + ma.height.max(mb.height),
                    });
                    stack.pop();
                }
                (ma, mb) => {
                    if ma.is_none() {
                        stack.push(a);
                    }
                    if mb.is_none() {
                        stack.push(b);
                    }
                }
            },
            _ => {
                memo[top] = Some(CsgMemo {
                    leaves: 1,
                    height: 0,
                });
                stack.pop();
            }
        }
    }
    memo[id].expect("computed above")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Node;
    use glam::DMat4;

    fn node(name: &str, kind: NodeKind, children: Vec<NodeId>) -> Node {
        Node {
            name: name.into(),
            kind,
            matrix: DMat4::IDENTITY,
            children,
            material: None,
        }
    }

    fn sphere() -> NodeKind {
        NodeKind::Geometry {
            primitive: Primitive::Sphere,
            placement: DMat4::IDENTITY,
        }
    }

    /// A sphere (node 0) under `levels` nodes, node k (`level(k)`) over node k − 1.
    fn stacked_over_a_sphere(levels: usize, level: impl Fn(usize) -> Node) -> SceneGraph {
        let mut graph = SceneGraph::default();
        graph.nodes.push(node("s", sphere(), vec![]));
        graph.nodes.extend((1..=levels).map(level));
        graph
    }

    #[test]
    fn doubling_dag_is_counted_without_walking_it() {
        // n0 = sphere; n(k) has n(k-1) twice: 2^k spheres below n(k).
        let graph = stacked_over_a_sphere(60, |k| {
            node(&format!("n{k}"), NodeKind::Transform, vec![k - 1, k - 1])
        });
        let c = scene_cost(&graph, 40).unwrap();
        assert_eq!(c.objects, 1 << 40);
        assert_eq!(c.paths, (1 << 41) - 1);
        let c = scene_cost(&graph, 60).unwrap();
        assert_eq!(c.objects, 1 << 60);
        assert!(c.bytes() == u64::MAX || c.bytes() > 1 << 60);
    }

    #[test]
    fn counts_match_a_small_tree() {
        let mut graph = SceneGraph::default();
        graph.nodes.push(node("ab", sphere(), vec![]));
        graph
            .nodes
            .push(node("root", NodeKind::Transform, vec![0, 0]));
        let c = scene_cost(&graph, 1).unwrap();
        assert_eq!(c.objects, 2);
        // Two objects named "root/ab".
        assert_eq!(c.name_bytes, 2 * 7);
        assert_eq!(c.paths, 3);
    }

    #[test]
    fn shared_csg_trees_are_counted_once_per_node() {
        // c(k) = csg(c(k-1), c(k-1)): 2^k leaves; under one transform 10⁵ times.
        let mut graph = stacked_over_a_sphere(16, |k| {
            let op = crate::scene::CsgOp::Union;
            node(
                "c",
                NodeKind::Csg {
                    op,
                    a: k - 1,
                    b: k - 1,
                },
                vec![],
            )
        });
        let top = graph.nodes.len();
        graph
            .nodes
            .push(node("top", NodeKind::Transform, vec![16; 100_000]));
        let start = std::time::Instant::now();
        let c = scene_cost(&graph, top).unwrap();
        assert_eq!(c.objects, 100_000 << 16);
        assert!(start.elapsed().as_secs_f64() < 1.0, "{:?}", start.elapsed());
    }

    #[test]
    fn deep_chains_are_refused_even_when_shared() {
        let graph = stacked_over_a_sphere(300, |k| node("t", NodeKind::Transform, vec![k - 1]));
        assert!(matches!(
            scene_cost(&graph, 300),
            Err(FlattenError::TooDeep { .. })
        ));
        assert!(scene_cost(&graph, 200).is_ok());
    }
}
