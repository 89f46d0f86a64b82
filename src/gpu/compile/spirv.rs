//! The SPIR-V wgpu 30 hands a Vulkan driver for one of glint's entry points, rebuilt
//! outside wgpu so that it can be written to disk (`render --dump-kernels`) and compiled
//! on devices wgpu cannot open (`glint kernels` on RADV's null device).
//!
//! It follows wgpu-core 30.0.1 (`Device::create_shader_module`: WGSL parsed by naga,
//! the source kept as debug info when the instance has `InstanceFlags::DEBUG`) and
//! wgpu-hal 30.0.1's Vulkan backend (`adapter.rs`, the `naga_options` of `open`;
//! `device.rs`, `compile_stage` and `create_pipeline_layout`): the module reduced to the
//! one entry point and compacted (`process_overrides`), bindings renumbered densely in
//! binding order, and these writer options — SPIR-V 1.6 on a Vulkan 1.3 device, index
//! bounds `Restrict`, buffer and image-load bounds `Unchecked` where robustBufferAccess2
//! and robustImageAccess are enabled (else `Restrict`), loop bounding forced, integer
//! division checked, workgroup memory zeroed natively where the device can.

use crate::gpu::compile::shader::Entry;
use naga::back::spv;
use naga::proc::{BoundsCheckPolicies, BoundsCheckPolicy};
use std::collections::BTreeMap;

/// What in a Vulkan device changes the SPIR-V wgpu-hal writes for it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpirvTarget {
    /// The device's Vulkan version is 1.3 or later (SPIR-V 1.6; 1.2: SPIR-V 1.5).
    pub vulkan_1_3: bool,
    /// `VK_EXT_robustness2`'s robustBufferAccess2 is enabled: buffer bounds unchecked.
    pub robust_buffer_access2: bool,
    /// `robustImageAccess` (Vulkan 1.3 / `VK_EXT_image_robustness`): image loads unchecked.
    pub robust_image_access: bool,
    /// `shaderZeroInitializeWorkgroupMemory`: native zeroing, else naga's polyfill.
    pub zero_initialize_workgroup_memory: bool,
    /// The wgpu instance has `InstanceFlags::DEBUG` (debug builds, or `WGPU_DEBUG=1`):
    /// names and the WGSL source go into the SPIR-V as debug information.
    pub debug: bool,
}

impl SpirvTarget {
    /// A Vulkan 1.3 device with robustness2 and image robustness (RADV, NVIDIA, ANV and
    /// lavapipe as Mesa 22.3 ships them), with the debug flag of this build's wgpu
    /// instance as glint creates it.
    pub fn vulkan_1_3() -> SpirvTarget {
        SpirvTarget {
            vulkan_1_3: true,
            robust_buffer_access2: true,
            robust_image_access: true,
            zero_initialize_workgroup_memory: true,
            debug: instance_debug(),
        }
    }
}

/// Whether glint's wgpu instance has `InstanceFlags::DEBUG` (`gpu::device::context` builds its
/// instance from the defaults and the environment, as here).
pub fn instance_debug() -> bool {
    wgpu::InstanceFlags::default()
        .with_env()
        .contains(wgpu::InstanceFlags::DEBUG)
}

/// The label wgpu-core names the shader module's debug source by (`pipeline.rs`'s
/// `create_shader_module` label).
pub const MODULE_LABEL: &str = "glint tracer";

/// naga's writer options as wgpu-hal 30's Vulkan `open` sets them for `target` (glint
/// requests no shader feature, so the capability list is the always-available one), with
/// the binding map of the pipeline layout.
fn writer_options<'a>(
    target: SpirvTarget,
    binding_map: spv::BindingMap,
    debug_info: Option<spv::DebugInfo<'a>>,
) -> spv::Options<'a> {
    use spv::Capability as C;
    let capabilities = [
        C::Shader,
        C::Matrix,
        C::Sampled1D,
        C::Image1D,
        C::ImageQuery,
        C::DerivativeControl,
        C::StorageImageExtendedFormats,
        C::SampledCubeArray,
        C::SampleRateShading,
    ];
    let mut flags = spv::WriterFlags::empty();
    flags.set(spv::WriterFlags::DEBUG, target.debug);
    flags.set(spv::WriterFlags::LABEL_VARYINGS, true); // not a Qualcomm device
    flags.set(spv::WriterFlags::FORCE_POINT_SIZE, true);
    flags.set(
        spv::WriterFlags::PRINT_ON_RAY_QUERY_INITIALIZATION_FAIL
            | spv::WriterFlags::PRINT_ON_TRACE_RAYS_FAIL,
        target.debug,
    );
    let unchecked_if = |robust: bool| {
        if robust {
            BoundsCheckPolicy::Unchecked
        } else {
            BoundsCheckPolicy::Restrict
        }
    };
    spv::Options {
        lang_version: if target.vulkan_1_3 { (1, 6) } else { (1, 5) },
        flags,
        capabilities: Some(capabilities.into_iter().collect()),
        bounds_check_policies: BoundsCheckPolicies {
            index: BoundsCheckPolicy::Restrict,
            buffer: unchecked_if(target.robust_buffer_access2),
            image_load: unchecked_if(target.robust_image_access),
            binding_array: BoundsCheckPolicy::Unchecked,
        },
        zero_initialize_workgroup_memory: if target.zero_initialize_workgroup_memory {
            spv::ZeroInitializeWorkgroupMemoryMode::Native
        } else {
            spv::ZeroInitializeWorkgroupMemoryMode::Polyfill
        },
        force_loop_bounding: true,
        ray_query_initialization_tracking: true,
        use_storage_input_output_16: false,
        fake_missing_bindings: false,
        binding_map,
        debug_info,
        task_dispatch_limits: None, // only read by task shaders
        mesh_shader_primitive_indices_clamp: true,
        trace_ray_argument_validation: true,
        emit_int_div_checks: true,
    }
}

/// wgpu-hal's binding map for a pipeline of one bind group laid out as `layout`: each
/// binding number to its index among the layout's bindings in increasing order
/// (wgpu-core keeps a layout's entries sorted by binding; wgpu-hal numbers the Vulkan
/// bindings densely in that order).
pub fn dense_binding_map(layout: &[wgpu::BindGroupLayoutEntry]) -> spv::BindingMap {
    let mut numbers: Vec<u32> = layout.iter().map(|e| e.binding).collect();
    numbers.sort_unstable();
    numbers
        .into_iter()
        .enumerate()
        .map(|(dense, binding)| {
            (
                naga::ResourceBinding { group: 0, binding },
                spv::BindingInfo {
                    descriptor_set: 0,
                    binding: dense as u32,
                    binding_array_size: None,
                },
            )
        })
        .collect::<BTreeMap<_, _>>()
}

/// The SPIR-V words wgpu 30 would hand a `target` device for `entry` of `source` in a
/// pipeline whose one bind group is laid out as `layout` (`pipeline::layout_entries`).
/// Errors are naga's messages.
pub fn wgsl_to_spirv(
    source: &str,
    entry: Entry,
    layout: &[wgpu::BindGroupLayoutEntry],
    target: SpirvTarget,
) -> Result<Vec<u32>, String> {
    entry_spirv(source, entry, layout, target).map(|(words, _)| words)
}

/// [`wgsl_to_spirv`], with the names of the functions the entry point reaches (what
/// survives compaction).
pub fn entry_spirv(
    source: &str,
    entry: Entry,
    layout: &[wgpu::BindGroupLayoutEntry],
    target: SpirvTarget,
) -> Result<(Vec<u32>, Vec<String>), String> {
    let module = naga::front::wgsl::parse_str(source).map_err(|e| e.emit_to_string(source))?;
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|e| e.emit_to_string(source))?;
    let stage = naga::ShaderStage::Compute;
    let (module, info) = naga::back::pipeline_constants::process_overrides(
        &module,
        &info,
        Some((stage, entry.name())),
        &Default::default(),
    )
    .map_err(|e| e.to_string())?;
    let debug_info = target.debug.then_some(spv::DebugInfo {
        source_code: source,
        file_name: MODULE_LABEL,
        language: spv::SourceLanguage::WGSL,
    });
    let options = writer_options(target, dense_binding_map(layout), debug_info);
    let pipeline = spv::PipelineOptions {
        entry_point: entry.name().to_string(),
        shader_stage: stage,
    };
    let words =
        spv::write_vec(&module, &info, &options, Some(&pipeline)).map_err(|e| e.to_string())?;
    let functions = module.functions.iter().filter_map(|(_, f)| f.name.clone());
    Ok((words, functions.collect()))
}

/// SPIR-V words as the little-endian bytes of a `.spv` file.
pub fn spirv_bytes(words: &[u32]) -> Vec<u8> {
    words.iter().flat_map(|w| w.to_le_bytes()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::compile::kernel::{KernelConfig, KernelVariant};
    use crate::gpu::compile::shader::assemble_with;
    use crate::gpu::pipeline::layout_entries;
    use crate::pack::SceneFeatures;

    /// The render module's bindings are renumbered 0..n in binding order, as wgpu-hal
    /// does; the probe module's too.
    #[test]
    fn bindings_are_renumbered_densely_in_binding_order() {
        for entry in [Entry::Render, Entry::Probe] {
            let map = dense_binding_map(&layout_entries(entry, KernelConfig::default()));
            let dense: Vec<u32> = map.values().map(|b| b.binding).collect();
            assert_eq!(dense, (0..map.len() as u32).collect::<Vec<_>>());
            let first = map.keys().next().unwrap();
            assert_eq!(first.binding, 0, "globals stay at 0");
        }
        let render = dense_binding_map(&layout_entries(Entry::Render, KernelConfig::default()));
        // Binding 14 (csg_program) follows 0–8 and 11–13: 12 bindings below it.
        let key = naga::ResourceBinding {
            group: 0,
            binding: 14,
        };
        assert_eq!(render[&key].binding, 12);
    }

    /// One SPIR-V module per entry, a valid header, and the same words every time (the
    /// megakernel `main`: the software variant's, the hardware variant's module has none).
    #[test]
    fn spirv_is_one_entry_point_and_deterministic() {
        let limits = wgpu::Limits::default();
        let kernel = KernelConfig::for_variant(KernelVariant::Software, &limits);
        let source = assemble_with(SceneFeatures::empty(), Entry::Render, kernel);
        let mut target = SpirvTarget::vulkan_1_3();
        target.debug = false;
        let layout = layout_entries(Entry::Render, kernel);
        let a = wgsl_to_spirv(&source, Entry::Render, &layout, target).unwrap();
        let b = wgsl_to_spirv(&source, Entry::Render, &layout, target).unwrap();
        assert_eq!(a, b);
        assert_eq!(a[0], 0x0723_0203, "SPIR-V magic");
        assert_eq!(a[1], 0x0001_0600, "SPIR-V 1.6");
        let other = wgsl_to_spirv(&source, Entry::AdaptiveDecide, &layout, target).unwrap();
        assert_ne!(a, other);
        assert!(other.len() < a.len(), "compacted to the entry's own code");
    }
}
