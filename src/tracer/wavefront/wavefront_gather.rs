//! The wavefront's gather pass (`wavefront_gather.wgsl` on the GPU): each vertex's colour
//! summed in `shade_phong`'s order (its own term, then each light's slot in light order,
//! an area light's strata in stratum order × 1/n²) into its sample's colour (chains) or
//! its vertex's value (trees, summed by the fold pass after the last generation).

use super::batch::{each_path, light_points, Batch, VertexKind};
use super::wavefront_tree::wavefront_fold;
use crate::constants::{LIGHT_AREA, SAMPLE_FINE_DETAIL};
use crate::pack::layout::load_light;
use crate::pack::PackedScene;
use crate::tracer::shading::shade::{add_stratum, area_light_mean, penumbra};
use crate::tracer::traversal::hit::TraversalCounters;
use glam::Vec3;

/// The gather pass: each vertex's colour into its sample's.
pub fn gather_pass(scene: &PackedScene, batch: &mut Batch, counters: &mut impl TraversalCounters) {
    each_path(scene, batch, counters, wavefront_gather);
}

/// The gather pass's invocation for path `i`: its vertex's colour as `shade_phong` sums
/// it (ambient, then each light in order: a point light's slot, an area light's strata
/// summed in stratum order and averaged, a penumbra at depth 0 noted in the sample's
/// hint), then into the sample's colour: the camera vertex's is the colour, a deeper
/// one's adds weight × colour (`trace_ray`'s order: generation order is its pop order).
// Mirror of src/tracer/wavefront/wavefront_gather.wgsl::wavefront_gather — change both.
fn wavefront_gather(
    scene: &PackedScene,
    batch: &mut Batch,
    i: usize,
    counters: &mut impl TraversalCounters,
) {
    let depth = batch.paths.depth[i];
    let k = batch.paths.sample[i] as usize;
    let mut colour = batch.vertices.own[i];
    if batch.vertices.kind[i] == VertexKind::Lit {
        let slots = &batch.slots.term[i * light_points(scene) as usize..];
        let mut slot = 0;
        for index in 0..scene.globals.num_lights {
            let light = load_light(scene, index);
            if light.kind == LIGHT_AREA {
                let strata = light.samples * light.samples;
                let mut sum = Vec3::ZERO;
                let mut lit = 0;
                for _ in 0..strata {
                    add_stratum(&mut sum, &mut lit, slots[slot]);
                    slot += 1;
                }
                if penumbra(depth, lit, light.samples) {
                    batch.samples.set_flag(k, SAMPLE_FINE_DETAIL);
                    counters.partial_light();
                }
                colour += area_light_mean(sum, light.samples);
            } else {
                colour += slots[slot];
                slot += 1;
            }
        }
    }
    let value = if depth == 0 {
        colour
    } else {
        batch.paths.weight[i] * colour
    };
    if batch.keeps_tree {
        // A tree's values are summed by the fold, in `trace_ray`'s pop order.
        batch.tree.value[batch.vertex_base as usize + i] = value;
    } else if depth == 0 {
        batch.samples.colour[k] = value;
    } else {
        batch.samples.colour[k] += value;
    }
}

/// The fold pass (scenes with refraction, after the last generation): each sample's
/// colour from its vertex tree ([`wavefront_fold`]).
pub fn fold_pass(batch: &mut Batch) {
    wavefront_fold(
        &batch.tree,
        &batch.camera_vertices.index,
        &mut batch.samples.colour,
    );
}
