//! The register budgets of issue 38 (docs/gpu-kernels.md#register-budgets): a kernel compiled
//! for NAVI21 may not spill VGPRs or SGPRs, may use no scratch, and may use at most 128
//! VGPRs in wave32 (8 waves a SIMD), 96 (10 waves) if it is a traversal kernel.

use super::stats::KernelStats;

/// Most wave32 VGPRs of any kernel.
pub const MAX_VGPRS_WAVE32: u32 = 128;
/// Most wave32 VGPRs of a traversal kernel.
pub const MAX_TRAVERSAL_VGPRS_WAVE32: u32 = 96;

/// Which budgets `stats` breaks, each as a short phrase (none: within budget). Figures
/// the driver did not report break nothing.
pub fn budget_breaks(stats: &KernelStats, traversal: bool) -> Vec<String> {
    let mut breaks = Vec::new();
    if let Some(n @ 1..) = stats.spilled_vgprs {
        breaks.push(format!("{n} spilled VGPRs"));
    }
    if let Some(n @ 1..) = stats.spilled_sgprs {
        breaks.push(format!("{n} spilled SGPRs"));
    }
    if let Some(n @ 1..) = stats.scratch_bytes {
        breaks.push(format!("{n} B scratch"));
    }
    if let (32, Some(v)) = (stats.wave, stats.vgprs) {
        let (limit, what) = if traversal {
            (MAX_TRAVERSAL_VGPRS_WAVE32, "traversal kernel")
        } else {
            (MAX_VGPRS_WAVE32, "kernel")
        };
        if v > limit {
            breaks.push(format!("{v} VGPRs > {limit} ({what}, wave32)"));
        }
    }
    breaks
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stats(wave: u32, vgprs: u32, spills: u32, scratch: u32) -> KernelStats {
        KernelStats {
            wave,
            vgprs: Some(vgprs),
            spilled_vgprs: Some(spills),
            spilled_sgprs: Some(0),
            scratch_bytes: Some(scratch),
            ..Default::default()
        }
    }

    #[test]
    fn each_budget_is_checked() {
        assert!(budget_breaks(&stats(32, 128, 0, 0), false).is_empty());
        assert!(budget_breaks(&stats(32, 96, 0, 0), true).is_empty());
        assert_eq!(
            budget_breaks(&stats(32, 97, 0, 0), true),
            ["97 VGPRs > 96 (traversal kernel, wave32)"]
        );
        assert_eq!(budget_breaks(&stats(32, 136, 0, 0), false).len(), 1);
        // The VGPR budgets are wave32's; wave64 is held to no spills and no scratch.
        assert!(budget_breaks(&stats(64, 200, 0, 0), true).is_empty());
        assert_eq!(
            budget_breaks(&stats(64, 256, 43, 146_432), false),
            ["43 spilled VGPRs", "146432 B scratch"]
        );
    }
}
