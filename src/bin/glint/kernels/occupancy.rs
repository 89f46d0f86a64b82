//! AMD families by RADV's `RADV_FORCE_FAMILY` name and the hardware rule of how many
//! waves of a kernel one SIMD holds, from its register counts. The rule is LLVM's
//! (`AMDGPUBaseInfo.cpp`: `getMaxWavesPerEU`, `getTotalNumVGPRs`, `getVGPRAllocGranule`,
//! `getNumWavesPerEUWithNumVGPRs`) and Mesa's (`radv_get_max_waves`, which also caps
//! Polaris and VegaM at 8 and counts SGPRs before GFX10):
//!
//! | generation | max waves | VGPR file per lane, wave32 / wave64 | granule, wave32 / wave64 |
//! | --- | ---: | --- | --- |
//! | GFX6–9 (GCN: Tahiti … Vega) | 10 (8 on Polaris, VegaM) | — / 256 | — / 4 |
//! | GFX10 (RDNA1: Navi1x) | 20 | 1024 / 512 | 8 / 4 |
//! | GFX10.3 (RDNA2: Navi2x) | 16 | 1024 / 512 | 16 / 8 |
//! | GFX11 (RDNA3: Navi31/32) | 16 | 1536 / 768 | 24 / 12 |
//!
//! Before GFX10 SGPRs limit too: 800 a SIMD (512 on GFX6–7) in granules of 16 (8). LDS
//! would limit a kernel that uses much of it; glint's kernels use none (the LDS column
//! of `glint kernels` says so). RADV's own "Subgroups per SIMD" statistic is another
//! number: on GFX10+ it counts a wave64 as two wave32s.

/// An AMD shader generation, as the occupancy rule needs it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Gfx {
    Gfx6,
    Gfx7,
    Gfx8,
    Gfx9,
    Gfx10,
    Gfx10_3,
    Gfx11,
}

/// A family RADV's null device can pretend to be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Family {
    /// `RADV_FORCE_FAMILY`'s name, upper case.
    pub name: &'static str,
    pub gfx: Gfx,
}

/// Families and generations, by Mesa 22.3's names (`ac_get_family_name`).
const FAMILIES: &[(&str, Gfx)] = &[
    ("TAHITI", Gfx::Gfx6),
    ("PITCAIRN", Gfx::Gfx6),
    ("VERDE", Gfx::Gfx6),
    ("OLAND", Gfx::Gfx6),
    ("HAINAN", Gfx::Gfx6),
    ("BONAIRE", Gfx::Gfx7),
    ("KAVERI", Gfx::Gfx7),
    ("KABINI", Gfx::Gfx7),
    ("HAWAII", Gfx::Gfx7),
    ("TONGA", Gfx::Gfx8),
    ("ICELAND", Gfx::Gfx8),
    ("CARRIZO", Gfx::Gfx8),
    ("FIJI", Gfx::Gfx8),
    ("STONEY", Gfx::Gfx8),
    ("POLARIS10", Gfx::Gfx8),
    ("POLARIS11", Gfx::Gfx8),
    ("POLARIS12", Gfx::Gfx8),
    ("VEGAM", Gfx::Gfx8),
    ("VEGA10", Gfx::Gfx9),
    ("VEGA12", Gfx::Gfx9),
    ("VEGA20", Gfx::Gfx9),
    ("RAVEN", Gfx::Gfx9),
    ("RAVEN2", Gfx::Gfx9),
    ("RENOIR", Gfx::Gfx9),
    ("NAVI10", Gfx::Gfx10),
    ("NAVI12", Gfx::Gfx10),
    ("NAVI14", Gfx::Gfx10),
    ("NAVI21", Gfx::Gfx10_3),
    ("NAVI22", Gfx::Gfx10_3),
    ("NAVI23", Gfx::Gfx10_3),
    ("NAVI24", Gfx::Gfx10_3),
    ("VANGOGH", Gfx::Gfx10_3),
    ("REMBRANDT", Gfx::Gfx10_3),
    ("GFX1100", Gfx::Gfx11),
];

impl Family {
    /// The family named `name` (any case), or an error listing the known ones.
    pub fn parse(name: &str) -> Result<Family, String> {
        let upper = name.to_uppercase();
        FAMILIES
            .iter()
            .find(|(n, _)| *n == upper)
            .map(|&(name, gfx)| Family { name, gfx })
            .ok_or_else(|| {
                let known: Vec<&str> = FAMILIES.iter().map(|(n, _)| *n).collect();
                format!("unknown GPU family '{name}' (known: {})", known.join(", "))
            })
    }

    /// Most waves a SIMD holds whatever the kernel.
    pub fn max_waves(self) -> u32 {
        match self.gfx {
            Gfx::Gfx10 => 20,
            Gfx::Gfx10_3 | Gfx::Gfx11 => 16,
            _ if matches!(self.name, "POLARIS10" | "POLARIS11" | "POLARIS12" | "VEGAM") => 8,
            _ => 10,
        }
    }

    /// (VGPRs a SIMD has per lane, allocation granule) for waves of `wave` lanes.
    fn vgpr_file(self, wave: u32) -> (u32, u32) {
        let w32 = wave == 32;
        match self.gfx {
            Gfx::Gfx11 => {
                if w32 {
                    (1536, 24)
                } else {
                    (768, 12)
                }
            }
            Gfx::Gfx10_3 => {
                if w32 {
                    (1024, 16)
                } else {
                    (512, 8)
                }
            }
            Gfx::Gfx10 => {
                if w32 {
                    (1024, 8)
                } else {
                    (512, 4)
                }
            }
            _ => (256, 4),
        }
    }

    /// Waves of `wave` lanes of a kernel with `vgprs` and `sgprs` one SIMD holds.
    pub fn waves_per_simd(self, wave: u32, vgprs: u32, sgprs: u32) -> u32 {
        let align = |x: u32, a: u32| x.max(1).div_ceil(a) * a;
        let (file, granule) = self.vgpr_file(wave);
        let mut waves = self.max_waves().min(file / align(vgprs, granule));
        if self.gfx < Gfx::Gfx10 && sgprs > 0 {
            let (per_simd, granule) = if self.gfx >= Gfx::Gfx8 {
                (800, 16)
            } else {
                (512, 8)
            };
            waves = waves.min(per_simd / align(sgprs, granule));
        }
        waves.max(1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn family(name: &str) -> Family {
        Family::parse(name).unwrap()
    }

    /// The figures: RDNA2 min(16, 1024/align(v,16)) in wave32 and
    /// min(16, 512/align(v,8)) in wave64.
    #[test]
    fn rdna2_rule() {
        let navi21 = family("navi21");
        assert_eq!(navi21.waves_per_simd(64, 96, 128), 5);
        assert_eq!(navi21.waves_per_simd(64, 152, 128), 3);
        assert_eq!(navi21.waves_per_simd(64, 256, 128), 2);
        assert_eq!(navi21.waves_per_simd(64, 32, 128), 16);
        assert_eq!(navi21.waves_per_simd(64, 33, 128), 12); // 512 / 40
        assert_eq!(navi21.waves_per_simd(32, 128, 128), 8);
        assert_eq!(navi21.waves_per_simd(32, 96, 128), 10);
        assert_eq!(navi21.waves_per_simd(32, 97, 128), 9); // 1024 / 112
        assert_eq!(navi21.waves_per_simd(32, 64, 128), 16);
        assert_eq!(navi21.waves_per_simd(32, 1, 128), 16);
        // SGPRs never limit on RDNA.
        assert_eq!(navi21.waves_per_simd(32, 64, 10_000), 16);
    }

    #[test]
    fn rdna1_and_rdna3_rules() {
        let navi10 = family("NAVI10");
        assert_eq!(navi10.waves_per_simd(32, 40, 128), 20); // 1024 / 40 = 25, capped
        assert_eq!(navi10.waves_per_simd(32, 128, 128), 8);
        assert_eq!(navi10.waves_per_simd(64, 128, 128), 4);
        assert_eq!(navi10.waves_per_simd(64, 130, 128), 3); // 512 / 132
        let gfx1100 = family("gfx1100");
        assert_eq!(gfx1100.waves_per_simd(32, 96, 128), 16);
        assert_eq!(gfx1100.waves_per_simd(32, 100, 128), 12); // 1536 / 120
        assert_eq!(gfx1100.waves_per_simd(64, 100, 128), 7); // 768 / 108
    }

    /// GCN: 256 VGPRs in granules of 4, 10 waves (8 on Polaris), and SGPRs count.
    #[test]
    fn gcn_rule_counts_sgprs() {
        let vega = family("VEGA10");
        assert_eq!(vega.waves_per_simd(64, 24, 16), 10);
        assert_eq!(vega.waves_per_simd(64, 84, 16), 3);
        assert_eq!(vega.waves_per_simd(64, 24, 102), 7); // 800 / 112
        assert_eq!(family("polaris10").waves_per_simd(64, 24, 16), 8);
        assert_eq!(family("TAHITI").waves_per_simd(64, 24, 102), 4); // 512 / 104
    }

    #[test]
    fn unknown_family_is_named_with_the_known_ones() {
        let e = Family::parse("navi99").unwrap_err();
        assert!(
            e.contains("unknown GPU family 'navi99'") && e.contains("NAVI21"),
            "{e}"
        );
    }
}
