//! The window's surface and the pass that draws the progressive sums into it
//! (`shaders/view_present.wgsl`), on the tracer's own device; and the screenshot of what
//! was presented (`--screenshot`: the surface texture copied back before it is shown).

use glint::film::Film;
use glint::gpu::view::progressive::SumBuffer;
use glint::gpu::GpuContext;
use std::sync::Arc;
use wgpu::util::DeviceExt;
use winit::window::Window;

/// The present pass's uniform: film and surface sizes (`Present` in the WGSL).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PresentParams {
    film: [u32; 2],
    surface: [u32; 2],
}

/// Surface, its configuration and the present pipeline.
pub struct Presenter {
    pub surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
    /// Whether the surface's textures can be copied (for `--screenshot`).
    pub can_copy: bool,
}

/// What `present` did.
pub enum Presented {
    Shown,
    /// The surface was outdated or lost; it has been reconfigured (draw again).
    Reconfigured,
    /// Nothing to draw into now (the window is hidden, or acquiring timed out).
    Skipped,
}

impl Presenter {
    /// Configures `surface` (made from `window` on `ctx`'s instance) for `ctx`'s device:
    /// a non-sRGB 8-bit format where there is one (values are shown as glint's PNGs store
    /// them, without gamma), FIFO presentation (no tearing, no spinning).
    pub fn new(
        ctx: &GpuContext,
        surface: wgpu::Surface<'static>,
        window: &Arc<Window>,
    ) -> Result<Presenter, String> {
        let caps = surface.get_capabilities(&ctx.adapter);
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f,
                    wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
                )
            })
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| {
                format!(
                    "the adapter {} cannot present to this window",
                    ctx.info.name
                )
            })?;
        let can_copy = caps.usages.contains(wgpu::TextureUsages::COPY_SRC);
        let mut usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
        if can_copy {
            usage |= wgpu::TextureUsages::COPY_SRC;
        }
        let size = window.inner_size();
        let limit = ctx.device.limits().max_texture_dimension_2d;
        let (width, height) = surface_size(size.width, size.height, limit);
        let config = wgpu::SurfaceConfiguration {
            usage,
            format,
            width,
            height,
            present_mode: wgpu::PresentMode::Fifo,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&ctx.device, &config);
        let (pipeline, layout) = present_pipeline(&ctx.device, format);
        let params = ctx
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("present params"),
                contents: bytemuck::bytes_of(&PresentParams {
                    film: [1, 1],
                    surface: [1, 1],
                }),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            });
        Ok(Presenter {
            surface,
            config,
            pipeline,
            layout,
            params,
            can_copy,
        })
    }

    /// Follows the window's new size.
    pub fn resize(&mut self, ctx: &GpuContext, width: u32, height: u32) {
        if width == 0 || height == 0 {
            return;
        }
        let limit = ctx.device.limits().max_texture_dimension_2d;
        (self.config.width, self.config.height) = surface_size(width, height, limit);
        self.surface.configure(&ctx.device, &self.config);
    }

    /// Runs `encode` (the frame's tracing work, if any), then draws the sums of a
    /// `film` (width, height) into the surface and presents, in one submit; with
    /// `screenshot`, the presented pixels come back as a film too.
    pub fn present(
        &mut self,
        ctx: &GpuContext,
        sums: &SumBuffer,
        film: [u32; 2],
        encode: &dyn Fn(&mut wgpu::CommandEncoder),
        screenshot: bool,
    ) -> (Presented, Option<Film>) {
        let texture = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&ctx.device, &self.config);
                return (Presented::Reconfigured, None);
            }
            _ => {
                // Still do the tracing work, so refinement does not wait for the window.
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                encode(&mut encoder);
                ctx.queue.submit([encoder.finish()]);
                return (Presented::Skipped, None);
            }
        };
        let params = PresentParams {
            film,
            surface: [self.config.width, self.config.height],
        };
        ctx.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("present"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: sums.buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.params.as_entire_binding(),
                },
            ],
        });
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encode(&mut encoder);
        let view = texture.texture.create_view(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("present"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
        let copy = (screenshot && self.can_copy)
            .then(|| self.encode_copy(ctx, &mut encoder, &texture.texture));
        ctx.queue.submit([encoder.finish()]);
        let shot = copy.and_then(|c| c.read(ctx, self.config.format));
        ctx.queue.present(texture);
        (Presented::Shown, shot)
    }

    fn encode_copy(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        texture: &wgpu::Texture,
    ) -> SurfaceCopy {
        let (w, h) = (self.config.width, self.config.height);
        let row = (4 * w).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
            * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("screenshot"),
            size: u64::from(row) * u64::from(h),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row),
                    rows_per_image: Some(h),
                },
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
        SurfaceCopy { buffer, row, w, h }
    }
}

/// The surface's size for a window of `width`×`height`: at least 1×1, and scaled down
/// (keeping its shape) to fit the adapter's texture limit `limit`, which a window as
/// wide as a large image can pass (wgpu panics on such a surface; the present pass
/// scales the film to whatever size the surface has).
pub fn surface_size(width: u32, height: u32, limit: u32) -> (u32, u32) {
    let (width, height, limit) = (width.max(1), height.max(1), limit.max(1));
    let longest = width.max(height);
    if longest <= limit {
        return (width, height);
    }
    let scale = |side: u32| (u64::from(side) * u64::from(limit) / u64::from(longest)).max(1) as u32;
    (scale(width), scale(height))
}

/// A surface texture's copy on its way back.
struct SurfaceCopy {
    buffer: wgpu::Buffer,
    row: u32,
    w: u32,
    h: u32,
}

impl SurfaceCopy {
    /// The copied pixels as a film (8-bit values over 255), or None if it failed.
    fn read(self, ctx: &GpuContext, format: wgpu::TextureFormat) -> Option<Film> {
        let size = u64::from(self.row) * u64::from(self.h);
        let bytes = glint::gpu::upload::buffers::read_back(ctx, &self.buffer, size).ok()?;
        let bgra = matches!(
            format,
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
        );
        let mut film = Film::new(self.w, self.h);
        for y in 0..self.h {
            for x in 0..self.w {
                let at = (y * self.row + 4 * x) as usize;
                let p = &bytes[at..at + 4];
                let (r, g, b) = if bgra {
                    (p[2], p[1], p[0])
                } else {
                    (p[0], p[1], p[2])
                };
                film.set(x, y, [r, g, b].map(|c| f32::from(c) / 255.0));
            }
        }
        Some(film)
    }
}

/// The present pipeline and its bind group layout (sums, params).
fn present_pipeline(
    device: &wgpu::Device,
    format: wgpu::TextureFormat,
) -> (wgpu::RenderPipeline, wgpu::BindGroupLayout) {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("view present"),
        source: wgpu::ShaderSource::Wgsl(
            include_str!("../../../../shaders/view_present.wgsl").into(),
        ),
    });
    let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("present"),
        entries: &[
            entry(0, wgpu::BufferBindingType::Storage { read_only: true }),
            entry(1, wgpu::BufferBindingType::Uniform),
        ],
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("present"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("present"),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("present_vertex"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("present_fragment"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });
    (pipeline, layout)
}

#[cfg(test)]
mod tests {
    use super::surface_size;

    #[test]
    fn a_surface_wider_than_the_texture_limit_is_scaled_to_fit() {
        assert_eq!(surface_size(800, 600, 8192), (800, 600));
        assert_eq!(surface_size(0, 0, 8192), (1, 1));
        assert_eq!(surface_size(20_000, 10_000, 8192), (8192, 4096));
        assert_eq!(surface_size(100, 65_536, 16_384), (25, 16_384));
        assert_eq!(surface_size(1, 1_000_000, 8192), (1, 8192));
    }
}
