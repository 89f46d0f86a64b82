//! `GpuError`: every way the GPU tracer can fail, as a value (never a panic or a hang).
//! Each message says what to do next; most name `--backend cpu` as the fallback.

/// Why a GPU render (or device acquisition) failed.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter on the enabled backends (or none whose name matches `--adapter`).
    #[error("no GPU adapter found{}{}; use --backend cpu (glint info lists adapters)",
        .wanted.as_ref().map(|w| format!(" matching '{w}'")).unwrap_or_default(),
        if .available.is_empty() { String::new() } else { format!(" (available: {})", .available.join(", ")) })]
    NoAdapter {
        wanted: Option<String>,
        available: Vec<String>,
    },
    /// The adapter refused to create a device.
    #[error("cannot create a device on '{adapter}': {message}; use --backend cpu")]
    RequestDevice { adapter: String, message: String },
    /// The device was lost (driver reset, out of memory, …) during the render.
    #[error("the GPU device was lost: {0}; use --backend cpu")]
    DeviceLost(String),
    /// A packed array does not fit in one storage-buffer binding of this adapter.
    #[error("the scene's {array} array is {bytes} bytes, {excess} bytes over this adapter's max_storage_buffer_binding_size of {limit}; render with --backend cpu")]
    SceneTooLarge {
        array: &'static str,
        bytes: u64,
        limit: u64,
        excess: u64,
    },
    /// A traversal table does not fit in one texture of this adapter.
    #[error("the scene's {array} table is {texels} texels, {rows} rows of {row} where this adapter's max_texture_dimension_2d allows {limit}; render with --backend cpu")]
    TableTooLarge {
        array: &'static str,
        texels: u64,
        rows: u64,
        row: u64,
        limit: u64,
    },
    /// The assembled shader failed to parse or validate (a bug in glint).
    #[error("the GPU shader for features [{features}] does not compile (a glint bug; use --backend cpu):\n{message}")]
    Shader { features: String, message: String },
    /// An environment setting of the GPU tracer has a value it does not take.
    #[error("{var}={value:?}: expected {expected}")]
    Setting {
        var: &'static str,
        value: String,
        expected: &'static str,
    },
    /// wgpu reported a validation or out-of-memory error.
    #[error("GPU {what} failed: {message}; use --backend cpu")]
    Wgpu { what: &'static str, message: String },
    /// `--dump-kernels`: a kernel file could not be written.
    #[error("cannot write the kernel dump {path}: {message}")]
    Dump { path: String, message: String },
}
