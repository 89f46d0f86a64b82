//! Item bounds for the scene grid, computed from the packed rows (the grid itself only
//! sees boxes): analytic instances under their transforms, CSG objects from their
//! programs, and mesh instances from their meshes' boxes.

use super::layout::PackedInstance;
use crate::accel::aabb::Aabb;
use crate::constants::{
    CSG_DIFFERENCE, CSG_INDEX_MASK, CSG_INTERSECTION, CSG_LEAF, CSG_OP_SHIFT, KIND_CONE, KIND_CUBE,
    KIND_CYLINDER, KIND_SPHERE, KIND_TORUS,
};
use glam::Vec3;

/// World bounds of an instance: the unit sphere, unit cube, cylinder, cone or torus under
/// its transform.
pub fn instance_bounds(inst: &PackedInstance) -> Aabb {
    let rows = inst.object_to_world.map(|r| Vec3::new(r[0], r[1], r[2]));
    let translation = Vec3::new(
        inst.object_to_world[0][3],
        inst.object_to_world[1][3],
        inst.object_to_world[2][3],
    );
    let (centre, half) = match inst.kind {
        // Ellipsoid: the extent along world axis i is the length of row i.
        KIND_SPHERE => (
            translation,
            Vec3::new(rows[0].length(), rows[1].length(), rows[2].length()),
        ),
        // Unit cube around (½,½,½): half-extent ½·Σ|row i|.
        KIND_CUBE => (
            translation
                + Vec3::new(
                    rows[0].dot(Vec3::splat(0.5)),
                    rows[1].dot(Vec3::splat(0.5)),
                    rows[2].dot(Vec3::splat(0.5)),
                ),
            0.5 * Vec3::new(
                rows[0].abs().element_sum(),
                rows[1].abs().element_sum(),
                rows[2].abs().element_sum(),
            ),
        ),
        // Cylinder and cone: their object-space box (centre c, half-extent h) under the
        // transform, half-extent Σ_j |row i|_j · h_j (conservative).
        KIND_CYLINDER | KIND_CONE => {
            let (c, h) = if inst.kind == KIND_CYLINDER {
                (Vec3::new(0.0, 0.0, 0.5), Vec3::new(1.0, 1.0, 0.5))
            } else {
                let [zmin, zmax] = inst.params;
                let r = zmin.abs().max(zmax.abs());
                (
                    Vec3::new(0.0, 0.0, 0.5 * (zmin + zmax)),
                    Vec3::new(r, r, 0.5 * (zmax - zmin)),
                )
            };
            (
                translation + Vec3::new(rows[0].dot(c), rows[1].dot(c), rows[2].dot(c)),
                Vec3::new(
                    rows[0].abs().dot(h),
                    rows[1].abs().dot(h),
                    rows[2].abs().dot(h),
                ),
            )
        }
        // Box [−R, R]² × [−rout, rout] (R = rin + rout) around the origin: half-extent
        // Σ|row i|·(R, R, rout).
        KIND_TORUS => {
            let [rin, rout] = inst.params;
            let extent = Vec3::new(rin + rout, rin + rout, rout);
            (
                translation,
                Vec3::new(
                    rows[0].abs().dot(extent),
                    rows[1].abs().dot(extent),
                    rows[2].abs().dot(extent),
                ),
            )
        }
        other => unreachable!("instance kind {other} has no bounds"),
    };
    Aabb {
        min: centre - half,
        max: centre + half,
    }
}

/// World bounds of a CSG object from its post-order `program` (entries as in
/// `PackedScene::csg_program`; leaves index `instances`): a union is bounded by the union
/// of its operands' bounds, an intersection by their intersection, a difference by a's.
/// Empty when an intersection's operands cannot overlap (the object is then in no cell).
pub fn csg_bounds(program: &[u32], instances: &[PackedInstance]) -> Aabb {
    let mut stack: Vec<Aabb> = Vec::new();
    for &entry in program {
        let op = entry >> CSG_OP_SHIFT;
        if op == CSG_LEAF {
            stack.push(instance_bounds(
                &instances[(entry & CSG_INDEX_MASK) as usize],
            ));
            continue;
        }
        let b = stack.pop().expect("CSG program: operand b");
        let a = stack.pop().expect("CSG program: operand a");
        stack.push(match op {
            CSG_INTERSECTION => a.intersection(b),
            CSG_DIFFERENCE => a,
            _ => a.union(b),
        });
    }
    let bounds = stack.pop().expect("CSG program: result");
    if bounds.is_empty() {
        Aabb::EMPTY
    } else {
        bounds
    }
}

/// World bounds of a mesh instance whose mesh has the box `mesh_bounds` in its own space:
/// the box's centre and half-extent under the instance's transform (conservative).
pub fn mesh_instance_bounds(inst: &PackedInstance, mesh_bounds: Aabb) -> Aabb {
    if mesh_bounds.is_empty() {
        return Aabb::EMPTY;
    }
    let rows = inst.object_to_world;
    let centre = (mesh_bounds.min + mesh_bounds.max) * 0.5;
    let half = (mesh_bounds.max - mesh_bounds.min) * 0.5;
    let mut min = Vec3::ZERO;
    let mut max = Vec3::ZERO;
    for axis in 0..3 {
        let row = Vec3::new(rows[axis][0], rows[axis][1], rows[axis][2]);
        let c = row.dot(centre) + rows[axis][3];
        let h = row.abs().dot(half);
        min[axis] = c - h;
        max[axis] = c + h;
    }
    Aabb { min, max }
}
