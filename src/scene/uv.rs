//! UVs of mesh triangles given none: a planar projection in the mesh's object space,
//! chosen per triangle by the dominant axis of its normal (a box projection), so every
//! face of a closed mesh gets a non-degenerate mapping and the texture moves with the
//! object. One object-space unit is one texture period:
//! - normal mostly along x: (u, v) = (y, z);
//! - mostly along y: (u, v) = (z, x);
//! - mostly along z: (u, v) = (x, y).
//!
//! (cyclic pairs, so ∂p/∂u × ∂p/∂v points along +axis: the texture reads unmirrored from
//! the positive side of the axis, mirrored from the negative side). Ties go to the
//! earlier axis (x before y before z).

use glam::DVec3;

/// The projected UVs of the object-space triangle `p`.
pub fn planar_uvs(p: [DVec3; 3]) -> [[f32; 2]; 3] {
    let n = (p[1] - p[0]).cross(p[2] - p[0]).abs();
    let project = |q: DVec3| -> [f32; 2] {
        if n.x >= n.y && n.x >= n.z {
            [q.y as f32, q.z as f32]
        } else if n.y >= n.z {
            [q.z as f32, q.x as f32]
        } else {
            [q.x as f32, q.y as f32]
        }
    };
    p.map(project)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_dominant_normal_axis_picks_the_plane() {
        let floor = [
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 3.0),
        ];
        assert_eq!(planar_uvs(floor), [[0.0, 0.0], [0.0, 1.0], [3.0, 0.0]]);
        let wall = [
            DVec3::new(5.0, 0.0, 0.0),
            DVec3::new(5.0, 1.0, 0.0),
            DVec3::new(5.0, 0.0, 2.0),
        ];
        assert_eq!(planar_uvs(wall), [[0.0, 0.0], [1.0, 0.0], [0.0, 2.0]]);
        let front = [
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.5),
            DVec3::new(0.0, 1.0, 0.5),
        ];
        assert_eq!(planar_uvs(front), [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    }
}
