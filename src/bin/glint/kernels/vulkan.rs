//! The instrument's Vulkan side, below wgpu (whose `request_device` fails on RADV's null
//! device: its winsys cannot submit). A device with what wgpu 30 enables that changes
//! code generation (robustBufferAccess, robustBufferAccess2 and robustImageAccess2,
//! robustImageAccess, native workgroup zeroing) plus `pipelineExecutableInfo`; each kernel
//! compiled as a compute pipeline with `VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR`
//! (and a required subgroup size when asked) and its executable statistics read back.
//! Nothing is allocated, recorded or submitted.

use super::stats::KernelStats;
use ash::vk;
use glint::gpu::compile::kernel::KernelConfig;
use glint::gpu::compile::shader::Entry;
use glint::gpu::pipeline::layout_entries;
use std::ffi::CStr;

/// A Vulkan device that compiles kernels and reports their statistics.
pub struct StatsDevice {
    _entry: ash::Entry,
    instance: ash::Instance,
    device: ash::Device,
    executables: ash::khr::pipeline_executable_properties::Device,
    /// The device's name, as its driver gives it ("AMD RADV NAVI21").
    pub name: String,
    /// Subgroup sizes a compute kernel may require (empty: none can be required).
    pub subgroup_sizes: Vec<u32>,
    /// The device's default subgroup size (on GCN the only one: 64).
    pub default_subgroup_size: u32,
}

/// Why the instrument could not start or compile.
#[derive(Debug, thiserror::Error)]
pub enum StatsError {
    #[error("cannot load the Vulkan loader (libvulkan.so.1): {0}; install libvulkan1 (Debian: apt-get install libvulkan1 mesa-vulkan-drivers)")]
    NoLoader(String),
    #[error("{what} failed: {result}")]
    Vulkan {
        what: &'static str,
        result: vk::Result,
    },
    #[error("{0}")]
    NoDevice(String),
}

fn check<T>(what: &'static str, r: Result<T, vk::Result>) -> Result<T, StatsError> {
    r.map_err(|result| StatsError::Vulkan { what, result })
}

const EXECUTABLE_PROPERTIES: &CStr = ash::khr::pipeline_executable_properties::NAME;
const ROBUSTNESS2: &CStr = ash::ext::robustness2::NAME;

fn device_name(instance: &ash::Instance, physical: vk::PhysicalDevice) -> String {
    let props = unsafe { instance.get_physical_device_properties(physical) };
    props
        .device_name_as_c_str()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn has_extension(instance: &ash::Instance, physical: vk::PhysicalDevice, name: &CStr) -> bool {
    let exts = unsafe { instance.enumerate_device_extension_properties(physical) };
    exts.unwrap_or_default()
        .iter()
        .any(|e| e.extension_name_as_c_str() == Ok(name))
}

/// The physical device to use: RADV's (the only one the loader sees under
/// `super::driver_env`) when `radv` is set, else the first non-CPU device with
/// `VK_KHR_pipeline_executable_properties`.
fn pick_device(instance: &ash::Instance, radv: bool) -> Result<vk::PhysicalDevice, StatsError> {
    let devices = check("vkEnumeratePhysicalDevices", unsafe {
        instance.enumerate_physical_devices()
    })?;
    let mut seen = Vec::new();
    for &physical in &devices {
        let props = unsafe { instance.get_physical_device_properties(physical) };
        let name = device_name(instance, physical);
        let stats = has_extension(instance, physical, EXECUTABLE_PROPERTIES);
        let cpu = props.device_type == vk::PhysicalDeviceType::CPU;
        if stats && (radv && name.contains("RADV") || !radv && !cpu) {
            return Ok(physical);
        }
        seen.push(format!(
            "{name} ({}{})",
            if cpu { "CPU, " } else { "" },
            if stats {
                "has statistics"
            } else {
                "no VK_KHR_pipeline_executable_properties"
            }
        ));
    }
    let listed = if seen.is_empty() {
        "none".to_string()
    } else {
        seen.join(", ")
    };
    Err(StatsError::NoDevice(if radv {
        format!("RADV offers no null device for this family (Vulkan devices: {listed}); is Mesa's RADV (mesa-vulkan-drivers) installed?")
    } else {
        format!("no hardware Vulkan device reports compiler statistics (devices: {listed}); name a chip with --family to compile on RADV's null device")
    }))
}

impl StatsDevice {
    /// Loads Vulkan and opens the device ([`pick_device`]).
    pub fn open(radv: bool) -> Result<StatsDevice, StatsError> {
        let entry =
            unsafe { ash::Entry::load() }.map_err(|e| StatsError::NoLoader(e.to_string()))?;
        let app = vk::ApplicationInfo::default()
            .application_name(c"glint kernels")
            .api_version(vk::API_VERSION_1_3);
        let instance = check("vkCreateInstance", unsafe {
            entry.create_instance(
                &vk::InstanceCreateInfo::default().application_info(&app),
                None,
            )
        })?;
        let physical = pick_device(&instance, radv)?;
        let name = device_name(&instance, physical);
        let mut size_control = vk::PhysicalDeviceSubgroupSizeControlProperties::default();
        let mut subgroup = vk::PhysicalDeviceSubgroupProperties::default();
        let mut props2 = vk::PhysicalDeviceProperties2::default()
            .push_next(&mut size_control)
            .push_next(&mut subgroup);
        unsafe { instance.get_physical_device_properties2(physical, &mut props2) };
        let api = props2.properties.api_version;
        let mut subgroup_sizes = Vec::new();
        if api >= vk::API_VERSION_1_3
            && size_control
                .required_subgroup_size_stages
                .contains(vk::ShaderStageFlags::COMPUTE)
        {
            let mut s = size_control.min_subgroup_size.max(1);
            while s <= size_control.max_subgroup_size {
                subgroup_sizes.push(s);
                s *= 2;
            }
        }
        let device = Self::create_device(&instance, physical, api)?;
        let executables = ash::khr::pipeline_executable_properties::Device::new(&instance, &device);
        Ok(StatsDevice {
            _entry: entry,
            instance,
            device,
            executables,
            name,
            subgroup_sizes,
            default_subgroup_size: subgroup.subgroup_size,
        })
    }

    /// The logical device, with the features wgpu 30 enables that change code
    /// generation where the device has them, and `pipelineExecutableInfo`.
    fn create_device(
        instance: &ash::Instance,
        physical: vk::PhysicalDevice,
        api: u32,
    ) -> Result<ash::Device, StatsError> {
        let mut have13 = vk::PhysicalDeviceVulkan13Features::default();
        let mut have_r2 = vk::PhysicalDeviceRobustness2FeaturesEXT::default();
        let r2 = has_extension(instance, physical, ROBUSTNESS2);
        let mut have = vk::PhysicalDeviceFeatures2::default();
        if api >= vk::API_VERSION_1_3 {
            have = have.push_next(&mut have13);
        }
        if r2 {
            have = have.push_next(&mut have_r2);
        }
        unsafe { instance.get_physical_device_features2(physical, &mut have) };
        let core = vk::PhysicalDeviceFeatures::default()
            .robust_buffer_access(have.features.robust_buffer_access == vk::TRUE);
        let mut v13 = vk::PhysicalDeviceVulkan13Features::default()
            .robust_image_access(have13.robust_image_access == vk::TRUE)
            .subgroup_size_control(have13.subgroup_size_control == vk::TRUE)
            .shader_zero_initialize_workgroup_memory(
                have13.shader_zero_initialize_workgroup_memory == vk::TRUE,
            );
        let mut robust2 = vk::PhysicalDeviceRobustness2FeaturesEXT::default()
            .robust_buffer_access2(have_r2.robust_buffer_access2 == vk::TRUE)
            .robust_image_access2(have_r2.robust_image_access2 == vk::TRUE);
        let mut exec = vk::PhysicalDevicePipelineExecutablePropertiesFeaturesKHR::default()
            .pipeline_executable_info(true);
        let mut extensions = vec![EXECUTABLE_PROPERTIES.as_ptr()];
        if r2 {
            extensions.push(ROBUSTNESS2.as_ptr());
        }
        let priorities = [1.0f32];
        let queues = [vk::DeviceQueueCreateInfo::default()
            .queue_family_index(0)
            .queue_priorities(&priorities)];
        let mut info = vk::DeviceCreateInfo::default()
            .queue_create_infos(&queues)
            .enabled_extension_names(&extensions)
            .enabled_features(&core)
            .push_next(&mut exec);
        if api >= vk::API_VERSION_1_3 {
            info = info.push_next(&mut v13);
        }
        if r2 {
            info = info.push_next(&mut robust2);
        }
        check("vkCreateDevice", unsafe {
            instance.create_device(physical, &info, None)
        })
    }

    /// Compiles `spirv` (entry `entry`, bindings as wgpu lays them out for `kernel`) with
    /// subgroup size `wave` (None: the driver's default) and reads its statistics.
    pub fn compile(
        &self,
        spirv: &[u32],
        entry: Entry,
        kernel: KernelConfig,
        wave: Option<u32>,
    ) -> Result<KernelStats, StatsError> {
        let d = &self.device;
        let mut numbers: Vec<(u32, vk::DescriptorType)> = layout_entries(entry, kernel)
            .iter()
            .map(|e| (e.binding, descriptor_type(e.ty)))
            .collect();
        numbers.sort_unstable_by_key(|&(b, _)| b);
        let bindings: Vec<vk::DescriptorSetLayoutBinding> = numbers
            .iter()
            .enumerate()
            .map(|(dense, &(_, ty))| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(dense as u32)
                    .descriptor_type(ty)
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::COMPUTE)
            })
            .collect();
        let set_layout = check("vkCreateDescriptorSetLayout", unsafe {
            d.create_descriptor_set_layout(
                &vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings),
                None,
            )
        })?;
        let layouts = [set_layout];
        let layout = check("vkCreatePipelineLayout", unsafe {
            d.create_pipeline_layout(
                &vk::PipelineLayoutCreateInfo::default().set_layouts(&layouts),
                None,
            )
        })?;
        let module = check("vkCreateShaderModule", unsafe {
            d.create_shader_module(&vk::ShaderModuleCreateInfo::default().code(spirv), None)
        })?;
        let result = self.pipeline_stats(module, layout, entry, wave);
        unsafe {
            d.destroy_shader_module(module, None);
            d.destroy_pipeline_layout(layout, None);
            d.destroy_descriptor_set_layout(set_layout, None);
        }
        result
    }

    fn pipeline_stats(
        &self,
        module: vk::ShaderModule,
        layout: vk::PipelineLayout,
        entry: Entry,
        wave: Option<u32>,
    ) -> Result<KernelStats, StatsError> {
        let name = std::ffi::CString::new(entry.name()).expect("entry names have no NUL");
        let mut required = vk::PipelineShaderStageRequiredSubgroupSizeCreateInfo::default()
            .required_subgroup_size(wave.unwrap_or(0));
        let mut stage = vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(module)
            .name(&name);
        if wave.is_some() {
            stage = stage.push_next(&mut required);
        }
        let info = vk::ComputePipelineCreateInfo::default()
            .flags(vk::PipelineCreateFlags::CAPTURE_STATISTICS_KHR)
            .stage(stage)
            .layout(layout);
        let pipeline = unsafe {
            self.device
                .create_compute_pipelines(vk::PipelineCache::null(), &[info], None)
        }
        .map_err(|(_, result)| StatsError::Vulkan {
            what: "vkCreateComputePipelines",
            result,
        })?[0];
        let stats = self.read_stats(pipeline);
        unsafe { self.device.destroy_pipeline(pipeline, None) };
        stats
    }

    fn read_stats(&self, pipeline: vk::Pipeline) -> Result<KernelStats, StatsError> {
        let info = vk::PipelineInfoKHR::default().pipeline(pipeline);
        let executables = check("vkGetPipelineExecutablePropertiesKHR", unsafe {
            self.executables.get_pipeline_executable_properties(&info)
        })?;
        let subgroup_size = executables.first().map_or(0, |e| e.subgroup_size);
        let exec = vk::PipelineExecutableInfoKHR::default()
            .pipeline(pipeline)
            .executable_index(0);
        let raw = check("vkGetPipelineExecutableStatisticsKHR", unsafe {
            self.executables.get_pipeline_executable_statistics(&exec)
        })?;
        let values = raw
            .iter()
            .map(|s| {
                let name = s.name_as_c_str().map(|n| n.to_string_lossy().into_owned());
                (name.unwrap_or_default(), statistic_value(s))
            })
            .collect();
        Ok(KernelStats::from_driver(subgroup_size, values))
    }
}

impl Drop for StatsDevice {
    fn drop(&mut self) {
        unsafe {
            self.device.destroy_device(None);
            self.instance.destroy_instance(None);
        }
    }
}

/// One statistic as a number (booleans as 0/1).
fn statistic_value(s: &vk::PipelineExecutableStatisticKHR) -> f64 {
    use vk::PipelineExecutableStatisticFormatKHR as F;
    unsafe {
        match s.format {
            F::BOOL32 => f64::from(s.value.b32),
            F::INT64 => s.value.i64 as f64,
            F::UINT64 => s.value.u64 as f64,
            F::FLOAT64 => s.value.f64,
            _ => f64::NAN,
        }
    }
}

/// The Vulkan descriptor type of a wgpu binding (the kinds glint's layouts use).
fn descriptor_type(ty: wgpu::BindingType) -> vk::DescriptorType {
    match ty {
        wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            ..
        } => vk::DescriptorType::UNIFORM_BUFFER,
        wgpu::BindingType::Buffer { .. } => vk::DescriptorType::STORAGE_BUFFER,
        wgpu::BindingType::StorageTexture { .. } => vk::DescriptorType::STORAGE_IMAGE,
        wgpu::BindingType::Sampler(_) => vk::DescriptorType::SAMPLER,
        _ => vk::DescriptorType::SAMPLED_IMAGE,
    }
}
