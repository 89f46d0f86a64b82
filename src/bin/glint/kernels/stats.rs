//! One compiled kernel's figures as a driver reports them through
//! `VK_KHR_pipeline_executable_properties`, by RADV's statistic names ("VGPRs", "SGPRs",
//! "Spilled VGPRs", "Spilled SGPRs", "Scratch size", "Code size", "LDS size",
//! "Instructions"); other drivers name other things, and what they do not report stays
//! `None` (shown as "—").

/// A kernel's register and memory figures.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct KernelStats {
    /// The subgroup (wave) size it was compiled for.
    pub wave: u32,
    pub vgprs: Option<u32>,
    pub sgprs: Option<u32>,
    pub spilled_vgprs: Option<u32>,
    pub spilled_sgprs: Option<u32>,
    /// Private memory per wave, bytes: spills and arrays moved to memory.
    pub scratch_bytes: Option<u32>,
    pub code_bytes: Option<u32>,
    pub lds_bytes: Option<u32>,
    pub instructions: Option<u32>,
    /// Every statistic the driver gave, by its name.
    pub all: Vec<(String, f64)>,
}

impl KernelStats {
    /// From the driver's (name, value) list.
    pub fn from_driver(wave: u32, all: Vec<(String, f64)>) -> KernelStats {
        let get = |names: &[&str]| {
            all.iter()
                .find(|(n, _)| names.contains(&n.as_str()))
                .map(|&(_, v)| v as u32)
        };
        KernelStats {
            wave,
            vgprs: get(&["VGPRs"]),
            sgprs: get(&["SGPRs"]),
            spilled_vgprs: get(&["Spilled VGPRs"]),
            spilled_sgprs: get(&["Spilled SGPRs"]),
            scratch_bytes: get(&["Scratch size", "Local Memory Size"]),
            code_bytes: get(&["Code size", "Binary Size"]),
            lds_bytes: get(&["LDS size", "Shared Memory Size"]),
            instructions: get(&["Instructions", "Instruction Count"]),
            all,
        }
    }
}
