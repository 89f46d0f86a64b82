//! `glint bench --trace --dump-rays FILE`: the geometry and the exact rays of a trace
//! benchmark, with glint's answers, for another tracer (the Embree harness in
//! `tools/benches/embree/`) to trace the same rays and count where it disagrees.
//!
//! Binary, little-endian, no padding (`tools/benches/embree/README.md` documents it too):
//! - header: `GLINTRAY` (8 bytes), then u32 version (1), triangles, instances, primary
//!   rays, shadow rays;
//! - per triangle: p0, p1, p2 (9 f32, world space: each mesh instance's triangles mapped
//!   by its transform; numbered after the instances, see [`ItemNumbering`]);
//! - per instance that is not a mesh (item number = its index here): u32 kind (`KIND_SPHERE` 0: unit sphere at the
//!   origin; `KIND_CUBE` 1: the box [0,1]³), world→object rows (12 f32), object→world
//!   rows (12 f32);
//! - per primary ray: origin (3 f32), unit direction (3 f32), t_max (f32: `T_MISS`,
//!   f32::MAX), glint's hit
//!   item (u32, `NO_ITEM` = 0xffffffff on a miss);
//! - per shadow ray: origin, unit direction, t_max (the light's distance), glint's
//!   answer (u32: 1 occluded, 0 not).
//!
//! Only spheres, boxes and triangles are written: the harness implements no other kind.

use glam::Vec3;
use glint::bench::trace_rays::{ItemNumbering, ShadowRay};
use glint::constants::{KIND_CUBE, KIND_MESH, KIND_SPHERE, T_MISS};
use glint::pack::PackedScene;
use glint::tracer::base::ray::Ray;
use glint::tracer::geometry::intersect::triangle_vertices;
use glint::tracer::traversal::traverse::Hit;
use glint::tracer::traversal::traverse_mesh::instance_mesh;
use std::io::Write;
use std::path::Path;

/// Format version written after the magic bytes.
pub const TRACE_DUMP_VERSION: u32 = 1;

/// An error unless every item is a sphere, a box or a triangle.
pub fn check_dumpable(scene: &PackedScene) -> anyhow::Result<()> {
    let items = &scene.instances[..scene.globals.num_instances as usize];
    if let Some(bad) = items
        .iter()
        .find(|i| i.kind != KIND_SPHERE && i.kind != KIND_CUBE && i.kind != KIND_MESH)
    {
        anyhow::bail!(
            "--dump-rays writes spheres, boxes and triangles only (what the Embree harness traces); this scene has an item of kind {} (cylinder 2, cone 3, torus 4, CSG 5)",
            bad.kind
        );
    }
    Ok(())
}

/// Writes the dump to a temporary file beside `path`, then renames it.
pub fn write_trace_dump(
    path: &Path,
    scene: &PackedScene,
    primary: &[Ray],
    hits: &[Hit],
    shadow: &[ShadowRay],
    occluded: &[bool],
) -> anyhow::Result<()> {
    check_dumpable(scene)?;
    glint::image_io::write_via_temp(path, |file| {
        write_to(file, scene, primary, hits, shadow, occluded)
    })
    .map_err(|e| e.context(format!("cannot write {}", glint::display_path::shown(path))))
}

fn write_to(
    file: &mut std::fs::File,
    scene: &PackedScene,
    primary: &[Ray],
    hits: &[Hit],
    shadow: &[ShadowRay],
    occluded: &[bool],
) -> anyhow::Result<()> {
    let mut out = std::io::BufWriter::new(file);
    let count = |n: usize| u32::try_from(n).map_err(|_| anyhow::anyhow!("{n} is over 2^32"));
    let instances = &scene.instances[..scene.globals.num_instances as usize];
    let (meshes, others): (Vec<_>, Vec<_>) = instances.iter().partition(|i| i.kind == KIND_MESH);
    let world_triangles: Vec<[Vec3; 3]> = meshes
        .iter()
        .flat_map(|inst| {
            let mesh = instance_mesh(scene, inst);
            let first = mesh.first_triangle as usize;
            let to_world = |p: Vec3| {
                let r = &inst.object_to_world;
                Vec3::new(
                    Vec3::from_slice(&r[0][..3]).dot(p) + r[0][3],
                    Vec3::from_slice(&r[1][..3]).dot(p) + r[1][3],
                    Vec3::from_slice(&r[2][..3]).dot(p) + r[2][3],
                )
            };
            scene.triangles[first..first + mesh.num_triangles as usize]
                .iter()
                .map(move |t| triangle_vertices(t).map(to_world))
        })
        .collect();
    let numbering = ItemNumbering::new(scene);
    out.write_all(b"GLINTRAY")?;
    for n in [
        TRACE_DUMP_VERSION,
        count(world_triangles.len())?,
        count(others.len())?,
        count(primary.len())?,
        count(shadow.len())?,
    ] {
        out.write_all(&n.to_le_bytes())?;
    }
    for t in &world_triangles {
        write_f32s(
            &mut out,
            t.iter()
                .flat_map(|p| p.to_array())
                .collect::<Vec<_>>()
                .iter(),
        )?;
    }
    for i in others {
        out.write_all(&i.kind.to_le_bytes())?;
        write_f32s(&mut out, i.world_to_object.iter().flatten())?;
        write_f32s(&mut out, i.object_to_world.iter().flatten())?;
    }
    for (ray, hit) in primary.iter().zip(hits) {
        write_ray(&mut out, ray, T_MISS, numbering.of(scene, hit))?;
    }
    for (s, &blocked) in shadow.iter().zip(occluded) {
        write_ray(&mut out, &s.ray, s.t_max, blocked as u32)?;
    }
    out.flush()?;
    Ok(())
}

fn write_ray(out: &mut impl Write, ray: &Ray, t_max: f32, answer: u32) -> std::io::Result<()> {
    write_f32s(out, ray.origin.to_array().iter().chain(&ray.dir.to_array()))?;
    write_f32s(out, [t_max].iter())?;
    out.write_all(&answer.to_le_bytes())
}

fn write_f32s<'a>(
    out: &mut impl Write,
    values: impl Iterator<Item = &'a f32>,
) -> std::io::Result<()> {
    for v in values {
        out.write_all(&v.to_le_bytes())?;
    }
    Ok(())
}
