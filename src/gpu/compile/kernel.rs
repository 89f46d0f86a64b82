//! The kernel variant a GPU context compiles, chosen from its adapter: the workgroup size,
//! whether traversal keeps per-ray mailboxes, whether loops check Mesa's limiter, where
//! per-ray lists live and whether the camera ray enters the secondary-ray loop.
//! None of them changes an answer (the tests render and probe every variant against the
//! CPU tracer); they change what the kernel costs on a given kind of device.

use crate::constants::WORKGROUP_SIZE;
use crate::gpu::compile::bindings::SCENE_TABLE_BINDINGS;
use crate::mailboxes::Mailboxes;
use std::fmt;

/// How the GPU tracer's shaders are specialised for one adapter (besides the scene's
/// features).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct KernelConfig {
    /// Side of the square workgroup of the 2-D kernels; the 1-D kernels run side² lanes.
    pub workgroup_side: u32,
    /// Which per-ray mailboxes the traversal keeps (the CPU twin's switch is
    /// `PackedScene::mailboxes`). They change no hit, only how often a primitive listed
    /// in several cells is tested.
    pub mailboxes: Mailboxes,
    /// Whether loops check Mesa's loop limiter (`ITERATION_GUARD`).
    pub iteration_guard: bool,
    /// Whether the scene's tables are bound as read-only storage textures
    /// (`STORAGE_TABLES`) rather than sampled ones: the same texels, read by another path.
    pub storage_tables: bool,
    /// Whether the per-ray lists that do not fit registers (the dielectric ray stack, the
    /// CSG interval lists) live in a storage buffer, one slot per invocation
    /// (`LISTS_IN_STORAGE`, `src/gpu/compile/lists.rs`), rather than in private arrays, which a
    /// GPU compiler puts in scratch memory.
    pub lists_in_storage: bool,
    /// Whether `trace_ray` takes the camera ray as the first entry of its loop over rays in
    /// scenes with mirrors but no dielectrics too (`CAMERA_RAY_IN_LOOP`, which
    /// `src/gpu/compile/shader.rs` sets for those and for every scene with dielectrics), rather
    /// than tracing and shading its hit before the loop. Either way the same steps run in
    /// the same order on the same values (the CPU twin's); the loop form inlines the
    /// traversal and shading once instead of twice.
    pub camera_ray_in_loop: bool,
    /// Whether `any_hit_inside` walks the scene grid and the pending mesh instances in one
    /// loop (`ANY_HIT_ONE_LOOP`: `occlusion_walk` takes one step a call) rather than a
    /// walk loop inside a loop over the pending batches. The same steps in the same
    /// order; one loop level fewer around the analytic tests spares a GPU the loop's
    /// masks and counters (RADV's scrabble.lua any-hit kernel spilled 6 SGPRs in wave64
    /// without it), while llvmpipe, which runs every branch of a loop body, would run the
    /// mesh walks masked beside every item test.
    pub any_hit_one_loop: bool,
    /// Whether AA none traces scenes through the wavefront kernels (`WAVEFRONT`,
    /// `src/tracer/wavefront/*.wgsl`: camera, closest hit, shading, shadow rays and gathering
    /// as kernels of their own joined by queues; with refraction also the vertex tree,
    /// glass shadow rounds and the fold of `src/tracer/wavefront/wavefront_tree.wgsl`) rather than the
    /// megakernel `main` (which the module then lacks). The images are the same bit for
    /// bit (the CPU twins are `tracer::wavefront`'s files beside them).
    pub wavefront: bool,
}

impl Default for KernelConfig {
    /// The hardware-GPU variant at the default workgroup size.
    fn default() -> KernelConfig {
        KernelConfig {
            workgroup_side: WORKGROUP_SIZE,
            mailboxes: Mailboxes::LastItem,
            iteration_guard: false,
            storage_tables: false,
            lists_in_storage: true,
            camera_ray_in_loop: true,
            any_hit_one_loop: true,
            wavefront: true,
        }
    }
}

impl KernelConfig {
    /// The variant for an adapter of `device_type` with `limits`:
    /// - workgroup: the largest square of side ≤ `WORKGROUP_SIZE` (8×8 = 64 lanes, a
    ///   multiple of every vendor's SIMD width: 32 on NVIDIA and Apple, 32/64 on AMD,
    ///   8–32 on Intel, 8 on llvmpipe's AVX2) that the adapter's invocation and size
    ///   limits allow. On lavapipe 4×4 measured slower on mesh scenes and 16×16 gave no
    ///   consistent gain (docs/journal/2026-11-29-gpu-kernel-variant-measured.md).
    /// - mailboxes: one slot (the last item tested) on every adapter. On software adapters
    ///   (device type Cpu: lavapipe, SwiftShader, WARP) llvmpipe turns a private array
    ///   indexed at run time into per-lane scatters and gathers that cost more than the
    ///   tests they save (17–38% of the render time on mesh scenes,
    ///   docs/journal/2026-11-29-gpu-kernel-variant-measured.md), while one slot is a
    ///   scalar and saves walking a mesh instance again in the next scene cell (3–17% less
    ///   GPU time where meshes span several cells, 5–8% more on demo without AA: the same
    ///   journal). On hardware the full caches lived in registers: up to 48 VGPRs of RADV's
    ///   NAVI21 kernels (nonhier.lua 160 → 112 in wave32), more than the budget's margin;
    ///   kept in the per-ray storage slots instead they cost the same registers as one slot
    ///   plus a load per lookup, a store per test and 8 + 32 stores to empty them per walk,
    ///   for 5–54% fewer primitive tests
    ///   (docs/journal/2026-12-02-mailboxes-out-of-registers.md; unmeasured on a GPU).
    /// - iteration guard: on software adapters, whose gallivm caps the loop iterations of
    ///   one invocation.
    /// - lists in storage: on hardware adapters, where RADV puts a private array over
    ///   256 bytes in scratch memory (glass.lua 60 KiB a wave for NAVI21, issue 38); on
    ///   software adapters private arrays stay, since llvmpipe runs a storage-buffer access
    ///   at lane-varying addresses as a loop over the lanes (docs/gpu.md) and keeps a
    ///   private array in memory anyway.
    /// - storage tables: on software adapters that bind as many storage textures as the
    ///   scene has tables. llvmpipe's image load skips the sampler's paths (a random read
    ///   measured 22–30% faster), and fetches are most of a frame there: a macho-cows
    ///   frame took 694M instructions instead of 1 294M (docs/journal/2026-12-01-storage-texture-tables.md); hardware keeps
    ///   sampled textures (unmeasured).
    /// - camera ray in the loop (with mirrors): on hardware adapters, where the camera
    ///   ray's hit traced and shaded before the loop inlines `closest_hit` and `shade_hit`
    ///   twice (RADV NAVI21: demo's kernels twice the code and spilled SGPRs,
    ///   docs/journal/2026-12-02-one-traversal-in-mirror-scenes.md); software adapters keep
    ///   the hit before the loop, since on llvmpipe a loop around the first hit cost
    ///   20–25% of the render (docs/journal/2026-11-30-one-hit-no-loop.md).
    /// - wavefront (AA none): on hardware adapters, where a megakernel's
    ///   registers are the traversal's plus everything live across it (RADV NAVI21:
    ///   112–176 VGPRs, docs/journal/2026-12-02-wavefront-split-measured.md); software
    ///   adapters keep the megakernel (unmeasured there: llvmpipe pays per dispatch and
    ///   for every queue's memory traffic).
    pub fn for_adapter(device_type: wgpu::DeviceType, limits: &wgpu::Limits) -> KernelConfig {
        let software = device_type == wgpu::DeviceType::Cpu;
        let tables = SCENE_TABLE_BINDINGS.len() as u32;
        KernelConfig {
            workgroup_side: workgroup_side_within(limits),
            mailboxes: Mailboxes::LastItem,
            iteration_guard: software,
            storage_tables: software && limits.max_storage_textures_per_shader_stage >= tables,
            lists_in_storage: !software,
            camera_ray_in_loop: !software,
            any_hit_one_loop: !software,
            wavefront: !software,
        }
    }

    /// The variant `--kernel-variant` forces: what [`KernelConfig::for_adapter`] would
    /// choose for a hardware or a software adapter with `limits` (so that the hardware
    /// kernels can be compiled, dumped and rendered on lavapipe, and the reverse).
    pub fn for_variant(variant: KernelVariant, limits: &wgpu::Limits) -> KernelConfig {
        let device_type = match variant {
            KernelVariant::Hardware => wgpu::DeviceType::DiscreteGpu,
            KernelVariant::Software => wgpu::DeviceType::Cpu,
        };
        KernelConfig::for_adapter(device_type, limits)
    }

    /// Lanes of a 1-D kernel's workgroup.
    pub fn linear_workgroup_size(&self) -> u32 {
        self.workgroup_side * self.workgroup_side
    }
}

/// `--kernel-variant`: the kernel variant glint would choose for a hardware or a software
/// adapter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum KernelVariant {
    Hardware,
    Software,
}

impl KernelVariant {
    /// The variant named `hardware` or `software`.
    pub fn parse(name: &str) -> Result<KernelVariant, String> {
        match name {
            "hardware" => Ok(KernelVariant::Hardware),
            "software" => Ok(KernelVariant::Software),
            _ => Err(format!(
                "kernel variant must be hardware or software, got '{name}'"
            )),
        }
    }
}

impl fmt::Display for KernelConfig {
    /// As `glint bench --gpu`, `glint info` and the shader header print it: "workgroup
    /// 8×8/64, last-item mailbox, iteration guard, storage-texture tables".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let side = self.workgroup_side;
        write!(
            f,
            "workgroup {side}×{side}/{}",
            self.linear_workgroup_size()
        )?;
        write!(f, ", {}", self.mailboxes)?;
        let switches = [
            (self.iteration_guard, "iteration guard"),
            (self.storage_tables, "storage-texture tables"),
            (self.lists_in_storage, "ray lists in storage"),
            (self.camera_ray_in_loop, "camera ray in loop"),
            (self.any_hit_one_loop, "any hit in one loop"),
            (self.wavefront, "wavefront"),
        ];
        for (_, name) in switches.iter().filter(|(on, _)| *on) {
            write!(f, ", {name}")?;
        }
        Ok(())
    }
}

/// The largest power-of-two side s ≤ `WORKGROUP_SIZE` with s² invocations and s × s
/// (and s² in x, for the 1-D kernels) within `limits`.
pub fn workgroup_side_within(limits: &wgpu::Limits) -> u32 {
    let mut side = WORKGROUP_SIZE;
    while side > 1 {
        let lanes = side * side;
        if lanes <= limits.max_compute_invocations_per_workgroup
            && lanes <= limits.max_compute_workgroup_size_x
            && side <= limits.max_compute_workgroup_size_y
        {
            break;
        }
        side /= 2;
    }
    side
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_adapter_keeps_one_mailbox_slot_and_software_ones_guard_loops() {
        let limits = wgpu::Limits::default();
        let soft = KernelConfig::for_adapter(wgpu::DeviceType::Cpu, &limits);
        assert!(soft.mailboxes == Mailboxes::LastItem && soft.iteration_guard);
        assert_eq!(
            soft.to_string(),
            "workgroup 8×8/64, last-item mailbox, iteration guard"
        );
        let hard = KernelConfig::for_adapter(wgpu::DeviceType::DiscreteGpu, &limits);
        // The full caches cost a hardware kernel up to 48 VGPRs (issue 38): one slot there too.
        assert!(hard.mailboxes == Mailboxes::LastItem && !hard.iteration_guard);
        assert!(hard.lists_in_storage && !soft.lists_in_storage);
        assert!(hard.camera_ray_in_loop && !soft.camera_ray_in_loop);
        assert!(hard.any_hit_one_loop && !soft.any_hit_one_loop);
        assert!(hard.wavefront && !soft.wavefront);
        assert_eq!(hard.workgroup_side, 8);
    }

    /// Storage-texture tables only on software adapters, and only where a stage may bind
    /// a storage texture for every table (WebGPU's default allows 4).
    #[test]
    fn storage_tables_on_software_adapters_that_bind_them_all() {
        let mut limits = wgpu::Limits::default();
        let soft = KernelConfig::for_adapter(wgpu::DeviceType::Cpu, &limits);
        assert!(
            !soft.storage_tables,
            "default limits: 4 storage textures a stage"
        );
        limits.max_storage_textures_per_shader_stage = SCENE_TABLE_BINDINGS.len() as u32;
        let soft = KernelConfig::for_adapter(wgpu::DeviceType::Cpu, &limits);
        assert!(soft.storage_tables);
        assert_eq!(
            soft.to_string(),
            "workgroup 8×8/64, last-item mailbox, iteration guard, storage-texture tables"
        );
        let hard = KernelConfig::for_adapter(wgpu::DeviceType::DiscreteGpu, &limits);
        assert!(!hard.storage_tables);
    }

    /// `--kernel-variant` gives each adapter kind's choice on any adapter.
    #[test]
    fn forced_variants_are_the_adapter_kinds_choices() {
        let limits = wgpu::Limits::default();
        let hard = KernelConfig::for_variant(KernelVariant::Hardware, &limits);
        assert_eq!(
            hard,
            KernelConfig::for_adapter(wgpu::DeviceType::IntegratedGpu, &limits)
        );
        assert_eq!(hard, KernelConfig::default());
        let soft = KernelConfig::for_variant(KernelVariant::Software, &limits);
        assert!(soft.iteration_guard && soft.mailboxes == Mailboxes::LastItem);
        assert_eq!(
            KernelVariant::parse("software"),
            Ok(KernelVariant::Software)
        );
        assert!(KernelVariant::parse("gpu")
            .unwrap_err()
            .contains("hardware or software"));
    }

    #[test]
    fn workgroup_side_respects_every_limit() {
        let mut limits = wgpu::Limits::default();
        assert_eq!(workgroup_side_within(&limits), 8);
        limits.max_compute_invocations_per_workgroup = 32;
        assert_eq!(workgroup_side_within(&limits), 4);
        limits.max_compute_invocations_per_workgroup = 256;
        limits.max_compute_workgroup_size_x = 16;
        assert_eq!(workgroup_side_within(&limits), 4);
        limits.max_compute_workgroup_size_x = 256;
        limits.max_compute_workgroup_size_y = 2;
        assert_eq!(workgroup_side_within(&limits), 2);
        limits.max_compute_invocations_per_workgroup = 1;
        assert_eq!(workgroup_side_within(&limits), 1);
    }
}
