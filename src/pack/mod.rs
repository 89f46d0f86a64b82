//! `pack`: the flattened [`FlatScene`] laid out as the Pod arrays both tracers read, plus the
//! grids over them: one over the scene's items, one per mesh over its triangles (see
//! `crate::accel`). Below this point there are no enums, only tags and indices.

pub mod bounds;
pub mod combinations;
pub mod environment;
pub mod features;
pub mod layout;
mod lights;
mod materials;
pub mod meshes;
pub mod procedural;
pub mod texture;

use crate::accel::aabb::Aabb;
use crate::accel::grid::{Grid, GridBuildStats};
use crate::constants::*;
pub use crate::mailboxes::Mailboxes;
use crate::scene::flatten::{CsgStep, FlatScene, Object, ObjectKind};
use crate::scene::{AaMode, Background, Camera, CsgOp, DebugView, GridMode};
use bounds::{csg_bounds, instance_bounds};
pub use features::SceneFeatures;
use glam::{DMat4, DVec3};
pub use layout::*;
use rayon::prelude::*;
pub use texture::texture_levels;

/// Everything a tracer needs, as flat arrays. The scene grid's items are the instances
/// `0..num_instances`: the analytic objects first, then one `KIND_CSG` instance per CSG
/// object, then one `KIND_MESH` instance per mesh placement; the leaves of the CSG
/// programs follow at `num_instances..` (not grid items). Triangles belong to meshes
/// (`meshes`), each traversed through its own grid.
#[derive(Clone, Debug)]
pub struct PackedScene {
    pub globals: PackedGlobals,
    pub instances: Vec<PackedInstance>,
    pub triangles: Vec<PackedTriangle>,
    /// Each mesh's triangle range and grid (`KIND_MESH` instances index it).
    pub meshes: Vec<PackedMesh>,
    pub materials: Vec<PackedMaterial>,
    pub lights: Vec<PackedLight>,
    /// `cell_start[c]..cell_start[c + 1]` indexes `cell_items` for cell c (x fastest):
    /// the scene grid's cells first, then each mesh's (from `PackedMesh::first_cell`).
    pub cell_start: Vec<u32>,
    pub cell_items: Vec<u32>,
    /// CSG programs, post-order (see `tracer::geometry::csg`); empty without CSG.
    pub csg_program: Vec<u32>,
    /// Texture table and texels (layout in [`texture`]); empty without textures.
    pub texels: Vec<u32>,
    /// Corner UVs of each triangle, parallel to `triangles`; empty unless the scene has
    /// the TEXTURE or BUMP feature.
    pub triangle_uvs: Vec<PackedTriangleUv>,
    /// Corner normals of each triangle (smooth shading), parallel to `triangles`; empty
    /// unless the scene has the SMOOTH feature.
    pub triangle_normals: Vec<PackedTriangleNormals>,
    pub features: SceneFeatures,
    /// Which per-ray mailboxes the CPU tracer's traversal keeps (`Mailboxes::Full`; the
    /// twin of the GPU kernel variant's, `gpu::KernelConfig`). They change no answer,
    /// only how often a primitive listed in several cells is tested; tests set each
    /// variant to show both tracers agree either way.
    pub mailboxes: Mailboxes,
    /// The scene grid's build counters.
    pub grid_stats: GridBuildStats,
    /// The mesh grids' counters, summed over the meshes.
    pub mesh_grid_stats: GridBuildStats,
}

impl PackedScene {
    /// The acceleration structure's memory and the triangles it stores: bytes of the
    /// stored triangles, both levels of grid cells and references, the mesh headers and
    /// the mesh instances (each triangle counted once however many instances share it).
    pub fn accel_memory(&self) -> (usize, usize) {
        use std::mem::size_of;
        let mesh_instances = self.instances[..self.globals.num_instances as usize]
            .iter()
            .filter(|i| i.kind == KIND_MESH)
            .count();
        let bytes = self.triangles.len() * size_of::<PackedTriangle>()
            + (self.cell_start.len() + self.cell_items.len()) * size_of::<u32>()
            + self.meshes.len() * size_of::<PackedMesh>()
            + mesh_instances * size_of::<PackedInstance>();
        (bytes, self.triangles.len())
    }
}

#[derive(Debug, thiserror::Error)]
pub enum PackError {
    #[error("light {index}: attenuation {falloff:?} is zero or negative at some distance (need c0, c1, c2 ≥ 0, not all 0)")]
    BadFalloff { index: usize, falloff: [f32; 3] },
    #[error("{what} {value} does not fit in f32 (scene coordinates must stay below ~1e38)")]
    OutOfRange { what: String, value: f64 },
    #[error("the scene has {0} items; glint supports at most 2^31")]
    TooManyItems(usize),
    #[error("the CSG objects have {0} primitives and program entries in all; glint supports at most 2^24")]
    CsgTooLarge(usize),
    #[error("the scene has {0} meshes; glint supports at most 2^24")]
    TooManyMeshes(usize),
}

/// The instance of an analytic object, and the feature its kind needs.
fn instance_of(o: &Object) -> (PackedInstance, SceneFeatures) {
    let (feature, kind, params) = match o.kind {
        ObjectKind::Sphere => (SceneFeatures::SPHERE, KIND_SPHERE, [0.0; 2]),
        ObjectKind::Cube => (SceneFeatures::CUBE, KIND_CUBE, [0.0; 2]),
        ObjectKind::Cylinder => (SceneFeatures::CYLINDER, KIND_CYLINDER, [0.0; 2]),
        ObjectKind::Cone { zmin, zmax } => (SceneFeatures::CONE, KIND_CONE, [zmin, zmax]),
        ObjectKind::Torus { rin, rout } => (SceneFeatures::TORUS, KIND_TORUS, [rin, rout]),
    };
    let instance = PackedInstance {
        world_to_object: affine_rows(&o.object_to_world.inverse()),
        object_to_world: affine_rows(&o.object_to_world),
        kind,
        material: o.material as u32,
        params,
    };
    (instance, feature)
}

/// The CSG objects packed: one `KIND_CSG` instance each, their leaf instances and the
/// programs of all of them, with the features the leaves need.
struct PackedCsg {
    items: Vec<PackedInstance>,
    leaves: Vec<PackedInstance>,
    program: Vec<u32>,
    features: SceneFeatures,
}

/// Packs the CSG objects, their leaves numbered from `first_leaf`.
fn pack_csg(scene: &FlatScene, first_leaf: usize) -> Result<PackedCsg, PackError> {
    let mut features = SceneFeatures::empty();
    let (mut items, mut leaves, mut program) = (Vec::new(), Vec::new(), Vec::new());
    for c in &scene.csg {
        let start = program.len();
        for step in &c.program {
            program.push(match step {
                CsgStep::Leaf(o) => {
                    let (instance, feature) = instance_of(o);
                    features.insert(feature);
                    let index = first_leaf + leaves.len();
                    leaves.push(instance);
                    if index > CSG_INDEX_MASK as usize {
                        return Err(PackError::CsgTooLarge(index));
                    }
                    (CSG_LEAF << CSG_OP_SHIFT) | index as u32
                }
                CsgStep::Op(op) => {
                    let code = match op {
                        CsgOp::Union => CSG_UNION,
                        CsgOp::Intersection => CSG_INTERSECTION,
                        CsgOp::Difference => CSG_DIFFERENCE,
                    };
                    code << CSG_OP_SHIFT
                }
            });
        }
        // Start and length travel as f32 (exact below 2^24; a bit pattern of a small
        // integer would be a denormal, which GPUs may flush to zero).
        if program.len() >= 1 << 24 {
            return Err(PackError::CsgTooLarge(program.len()));
        }
        features.insert(SceneFeatures::CSG);
        let identity = affine_rows(&DMat4::IDENTITY);
        items.push(PackedInstance {
            world_to_object: identity,
            object_to_world: identity,
            kind: KIND_CSG,
            material: c.material as u32,
            params: [start as f32, (program.len() - start) as f32],
        });
    }
    Ok(PackedCsg {
        items,
        leaves,
        program,
        features,
    })
}

/// Packs a flattened scene and builds its grid.
pub fn pack(scene: &FlatScene) -> Result<PackedScene, PackError> {
    let mut features = SceneFeatures::empty();
    let mut instances = analytic_instances(scene, &mut features);
    let (density, mesh_density) = grid_densities(scene.options.grid);
    // Materials first: whether the meshes' UVs are packed depends on their textures.
    // Procedural textures' words follow the images' in texels.
    let procedural_base = procedural::image_words(&scene.textures);
    let materials = materials::pack_materials(scene, procedural_base);
    features.insert(materials::material_features(scene, &materials));
    let mut meshes = meshes::pack_meshes(scene, mesh_density, features.uses_textures())?;
    // CSG objects and mesh instances are items after the analytic objects; the CSG
    // leaves follow all items.
    let num_items = instances.len() + scene.csg.len() + meshes.instances.len();
    let csg = pack_csg(scene, num_items)?;
    features.insert(csg.features);
    instances.extend(csg.items);
    instances.extend(std::mem::take(&mut meshes.instances));
    instances.extend(csg.leaves);
    let csg_program = csg.program;
    let triangles = std::mem::take(&mut meshes.triangles);
    if !triangles.is_empty() {
        features.insert(SceneFeatures::MESH);
    }
    let triangle_normals = if meshes.smooth {
        features.insert(SceneFeatures::SMOOTH);
        std::mem::take(&mut meshes.triangle_normals)
    } else {
        Vec::new()
    };
    check_finite(&instances, &triangles)?;
    let (mut texels, triangle_uvs) = if features.uses_textures() {
        let mut texels = texture::pack_texels(&scene.textures);
        if features.contains(SceneFeatures::PROCEDURAL) {
            texels.extend(procedural::pack_procedurals(
                &scene.materials,
                procedural_base,
            ));
        }
        (texels, std::mem::take(&mut meshes.triangle_uvs))
    } else {
        (Vec::new(), Vec::new())
    };
    let environment = scene.options.environment.as_ref().map(|map| {
        features.insert(SceneFeatures::ENVIRONMENT);
        environment::append_environment(&mut texels, map)
    });
    if scene.lights.iter().any(|l| l.area.is_some()) {
        features.insert(SceneFeatures::AREA_LIGHT);
    }
    if scene.options.aperture > 0.0 {
        features.insert(SceneFeatures::DEPTH_OF_FIELD);
    }
    let lights = lights::pack_lights(scene)?;
    check_limits(num_items)?;
    let bounds = item_bounds(&instances, &csg_program, num_items, &meshes.instance_bounds);
    // A scene grid over a single item could never cull it (the grid's bounds are the
    // item's): its DDA would only cost each ray a set-up and a cell walk. So the automatic
    // choice traverses such a scene by brute force; an explicit density is obeyed.
    let density =
        density.filter(|_| num_items > 1 || !matches!(scene.options.grid, GridMode::Auto));
    let grid = Grid::build(bounds, None, density);
    if grid.enabled {
        features.insert(SceneFeatures::GRID);
    }
    let (cell_start, cell_items) = all_cells(&grid, &mut meshes);
    let mut globals = make_globals(scene, num_items, &triangles, &lights, &grid);
    if let Some(start) = environment {
        let (cos, sin) = environment::rotation_cos_sin(scene.options.environment_rotation);
        globals.environment = start;
        globals.environment_cos = cos;
        globals.environment_sin = sin;
    }
    let packed = PackedScene {
        globals,
        instances,
        triangles,
        meshes: meshes.meshes,
        materials,
        lights,
        cell_start,
        cell_items,
        csg_program,
        texels,
        triangle_uvs,
        triangle_normals,
        features,
        mailboxes: Mailboxes::Full,
        grid_stats: grid.stats,
        mesh_grid_stats: meshes.stats,
    };
    Ok(packed)
}

/// The instances of the analytic objects, adding the features their kinds need.
fn analytic_instances(scene: &FlatScene, features: &mut SceneFeatures) -> Vec<PackedInstance> {
    scene
        .objects
        .iter()
        .map(|o| {
            let (instance, feature) = instance_of(o);
            features.insert(feature);
            instance
        })
        .collect()
}

/// The densities λ of the scene grid and of the mesh grids (`None`: no grid); an
/// explicit density sets both.
fn grid_densities(mode: GridMode) -> (Option<f32>, Option<f32>) {
    match mode {
        GridMode::Off => (None, None),
        GridMode::Auto => (
            Some(crate::accel::grid::DEFAULT_DENSITY),
            Some(crate::accel::grid::MESH_DEFAULT_DENSITY),
        ),
        GridMode::Density(d) => (Some(d), Some(d)),
    }
}

/// Rejects more items than the tracers can index.
fn check_limits(num_items: usize) -> Result<(), PackError> {
    if num_items >= (1 << 31) {
        return Err(PackError::TooManyItems(num_items));
    }
    Ok(())
}

/// World bounds of the scene grid's items: the analytic and CSG objects, then the mesh
/// instances (whose bounds `mesh_bounds` holds).
fn item_bounds(
    instances: &[PackedInstance],
    csg_program: &[u32],
    num_items: usize,
    mesh_bounds: &[Aabb],
) -> Vec<Aabb> {
    let num_scene_objects = num_items - mesh_bounds.len();
    instances[..num_scene_objects]
        .iter()
        .map(|inst| {
            if inst.kind == KIND_CSG {
                let start = inst.params[0] as usize;
                let end = start + inst.params[1] as usize;
                csg_bounds(&csg_program[start..end], instances)
            } else {
                instance_bounds(inst)
            }
        })
        .chain(mesh_bounds.iter().copied())
        .collect()
}

/// The cells of the scene grid followed by the mesh grids' (moved behind it):
/// `(cell_start, cell_items)`.
fn all_cells(grid: &Grid, meshes: &mut meshes::PackedMeshes) -> (Vec<u32>, Vec<u32>) {
    meshes.append_cells(grid.cell_start.len(), grid.cell_items.len());
    let mut cell_start = grid.cell_start.clone();
    cell_start.extend_from_slice(&meshes.cell_start);
    let mut cell_items = grid.cell_items.clone();
    cell_items.extend_from_slice(&meshes.cell_items);
    (cell_start, cell_items)
}

/// The camera's part of the globals: eye, unit forward, right and true up, tan(fov/2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraFrame {
    pub eye: [f32; 3],
    pub forward: [f32; 3],
    pub right: [f32; 3],
    pub up: [f32; 3],
    pub tan_half_fov: f32,
}

/// The camera frame primary rays are made from, computed in f64 and rounded once (the
/// one place it is computed: `glint view` moves the camera through it too).
pub fn camera_frame(camera: &Camera) -> CameraFrame {
    let forward = camera.view.normalize();
    let right = forward.cross(camera.up).normalize();
    let up = right.cross(forward);
    CameraFrame {
        eye: camera.eye.as_vec3().to_array(),
        forward: forward.as_vec3().to_array(),
        right: right.as_vec3().to_array(),
        up: up.as_vec3().to_array(),
        tan_half_fov: (camera.fov_deg.to_radians() * 0.5).tan() as f32,
    }
}

/// The globals uniform: camera frame, image size, background, counts, grid and options.
fn make_globals(
    scene: &FlatScene,
    num_items: usize,
    triangles: &[PackedTriangle],
    lights: &[PackedLight],
    grid: &Grid,
) -> PackedGlobals {
    let frame = camera_frame(&scene.camera);
    let (top, bottom) = match scene.options.background {
        Background::Solid(c) => (c, c),
        Background::Gradient { top, bottom } => (top, bottom),
    };
    let options = &scene.options;
    PackedGlobals {
        eye: frame.eye,
        tan_half_fov: frame.tan_half_fov,
        forward: frame.forward,
        aspect: scene.width as f32 / scene.height as f32,
        right: frame.right,
        width: scene.width,
        up: frame.up,
        height: scene.height,
        ambient: scene.ambient,
        num_lights: lights.len() as u32,
        background_top: top,
        max_depth: options.max_depth.get(),
        background_bottom: bottom,
        min_weight: options.min_weight,
        grid_min: grid.min,
        num_instances: num_items as u32,
        grid_cell_size: grid.cell_size,
        num_triangles: triangles.len() as u32,
        grid_dims: grid.dims,
        grid_enabled: grid.enabled as u32,
        grid_max: grid.max,
        aa_mode: match options.aa {
            AaMode::None => AA_NONE,
            AaMode::Uniform => AA_UNIFORM,
            AaMode::Adaptive => AA_ADAPTIVE,
        },
        aa_samples: options.samples.get(),
        aa_threshold: options.aa_threshold,
        aa_depth: options.aa_depth.get(),
        camera_media_count: 0,
        camera_media: [AIR_IOR; MEDIUM_STACK_SIZE as usize],
        debug_view: match options.debug {
            // The AA map is made from the render's own decisions.
            DebugView::None | DebugView::AaSamples => DEBUG_VIEW_NONE,
            DebugView::Uv => DEBUG_VIEW_UV,
        },
        lens_radius: options.aperture,
        focus_distance: options.focus.unwrap_or(scene.camera.view.length() as f32),
        // Set by `pack` when there is an environment map (zero, as the padding these
        // words were, without one).
        environment: 0,
        environment_cos: 0.0,
        environment_sin: 0.0,
        _pad0: 0,
        _pad1: 0,
    }
}

/// Rows of the 3×4 affine part of `m` (xyz linear, w translation), in f32.
pub(crate) fn affine_rows(m: &DMat4) -> [[f32; 4]; 3] {
    let r = m.transpose();
    [
        r.x_axis.as_vec4().to_array(),
        r.y_axis.as_vec4().to_array(),
        r.z_axis.as_vec4().to_array(),
    ]
}

/// Triangle indices in Morton (Z-curve) order of their centroids. Triangles near each
/// other in space then sit near each other in memory, so a ray walking the grid touches
/// few cache lines; with 10⁶ random triangles this keeps the per-ray cost close to that
/// of 10³. Ties keep input order, so the order is deterministic.
fn spatial_order(centroids: &[DVec3]) -> Vec<usize> {
    let (lo, hi) = centroids.iter().fold(
        (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
        |(lo, hi), &c| (lo.min(c), hi.max(c)),
    );
    let scale = (hi - lo).max(DVec3::splat(f64::MIN_POSITIVE)).recip() * 1023.0;
    let mut keyed: Vec<(u32, usize)> = centroids
        .par_iter()
        .enumerate()
        .map(|(i, &c)| {
            let q = ((c - lo) * scale).clamp(DVec3::ZERO, DVec3::splat(1023.0));
            (morton3(q.x as u32, q.y as u32, q.z as u32), i)
        })
        .collect();
    keyed.par_sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// Interleaves the low 10 bits of x, y and z (x lowest).
fn morton3(x: u32, y: u32, z: u32) -> u32 {
    fn spread(mut v: u32) -> u32 {
        v &= 0x3ff;
        v = (v | (v << 16)) & 0x0300_00ff;
        v = (v | (v << 8)) & 0x0300_f00f;
        v = (v | (v << 4)) & 0x030c_30c3;
        (v | (v << 2)) & 0x0924_9249
    }
    spread(x) | (spread(y) << 1) | (spread(z) << 2)
}

/// A zero-area triangle can never be hit (the watertight test rejects det = 0) but would
/// still cost grid space: drop it.
fn is_degenerate(p: &[DVec3; 3]) -> bool {
    (p[1] - p[0]).cross(p[2] - p[0]).length_squared() == 0.0
}

fn check_finite(
    instances: &[PackedInstance],
    triangles: &[PackedTriangle],
) -> Result<(), PackError> {
    for (i, inst) in instances.iter().enumerate() {
        let values = inst.world_to_object.iter().chain(&inst.object_to_world);
        if let Some(v) = values.flatten().find(|v| !v.is_finite()) {
            return Err(PackError::OutOfRange {
                what: format!("instance {i} transform entry"),
                value: *v as f64,
            });
        }
    }
    for (i, inst) in instances.iter().enumerate() {
        if let Some(v) = inst.params.iter().find(|v| !v.is_finite()) {
            return Err(PackError::OutOfRange {
                what: format!("instance {i} parameter"),
                value: *v as f64,
            });
        }
    }
    for (i, t) in triangles.iter().enumerate() {
        if let Some(v) = [t.p0, t.p1, t.p2].iter().flatten().find(|v| !v.is_finite()) {
            return Err(PackError::OutOfRange {
                what: format!("triangle {i} coordinate"),
                value: *v as f64,
            });
        }
    }
    Ok(())
}
