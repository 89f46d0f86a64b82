//! `glint kernels`' output: a markdown table (one row per scene, entry point and wave
//! size) or JSON (the same rows as objects), and the budget report of the rows that
//! break the register budgets.

use super::budget::budget_breaks;
use super::collect::Kernel;
use super::{Compiled, Measurement, Wave};
use std::fmt::Write;

/// One output row: a scene's kernel at one wave size.
pub struct Row<'a> {
    pub scene: &'a str,
    /// The scene's own AA mode dispatches this entry.
    pub dispatched: bool,
    pub kernel: &'a Kernel,
    pub compiled: &'a Compiled,
}

impl Row<'_> {
    /// Waves per SIMD by the family's rule, with the family's maximum.
    fn waves(&self, m: &Measurement) -> Option<(u32, u32)> {
        let (family, stats) = (m.family?, self.compiled.stats.as_ref().ok()?);
        let w = family.waves_per_simd(stats.wave, stats.vgprs?, stats.sgprs.unwrap_or(0));
        Some((w, family.max_waves()))
    }

    /// The budgets the row breaks (a kernel that did not compile breaks none here).
    pub fn breaks(&self) -> Vec<String> {
        match &self.compiled.stats {
            Ok(s) => budget_breaks(s, self.kernel.traversal),
            Err(_) => Vec::new(),
        }
    }
}

/// Every row, by scene (in the order given), entry point and wave size.
pub fn rows(m: &Measurement) -> Vec<Row<'_>> {
    let mut scenes: Vec<&str> = Vec::new();
    for k in &m.set.kernels {
        for (s, _) in &k.scenes {
            if !scenes.contains(&s.as_str()) {
                scenes.push(s);
            }
        }
    }
    let mut out = Vec::new();
    for scene in scenes {
        for c in &m.compiled {
            let kernel = &m.set.kernels[c.kernel];
            if let Some((_, dispatched)) = kernel.scenes.iter().find(|(s, _)| s == scene) {
                out.push(Row {
                    scene,
                    dispatched: *dispatched,
                    kernel,
                    compiled: c,
                });
            }
        }
    }
    out
}

fn opt(v: Option<u32>) -> String {
    v.map_or("—".to_string(), |v| v.to_string())
}

fn kib(v: Option<u32>) -> String {
    match v {
        Some(0) => "0".to_string(),
        Some(b) => format!("{:.1} KiB", f64::from(b) / 1024.0),
        None => "—".to_string(),
    }
}

fn wave_label(c: &Compiled) -> String {
    let actual = c.stats.as_ref().map(|s| s.wave).unwrap_or(0);
    match c.wave {
        Wave::Default => format!("{actual} (default)"),
        Wave::Required(n) => n.to_string(),
    }
}

/// The markdown table, after a line naming the device and the kernel variant.
pub fn table(m: &Measurement) -> String {
    let mut out = String::new();
    let family = m
        .family
        .map_or("its own chip".to_string(), |f| f.name.to_string());
    let variant = m.set.kernels.first().map(|k| k.kernel.to_string());
    let _ = writeln!(
        out,
        "device: {} ({family}); kernel: {}\n",
        m.device,
        variant.unwrap_or_default()
    );
    out += "| scene | entry | used | wave | VGPRs | SGPRs | spilled VGPRs / SGPRs | scratch per wave | code | LDS | waves per SIMD | budget |\n";
    out += "| --- | --- | --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | --- |\n";
    for row in rows(m) {
        let entry = format!(
            "{}{}",
            row.kernel.entry.name(),
            if row.kernel.traversal {
                " (traversal)"
            } else {
                ""
            }
        );
        let used = if row.dispatched { "yes" } else { "" };
        let wave = wave_label(row.compiled);
        match &row.compiled.stats {
            Err(e) => {
                let _ = writeln!(
                    out,
                    "| {} | {entry} | {used} | {wave} | {e} |||||||",
                    row.scene
                );
            }
            Ok(s) => {
                let waves = row
                    .waves(m)
                    .map_or("—".into(), |(w, max)| format!("{w} of {max}"));
                let breaks = row.breaks();
                let budget = if breaks.is_empty() {
                    "ok".into()
                } else {
                    breaks.join("; ")
                };
                let _ = writeln!(
                    out,
                    "| {} | {entry} | {used} | {wave} | {} | {} | {} / {} | {} | {} | {} | {waves} | {budget} |",
                    row.scene,
                    opt(s.vgprs),
                    opt(s.sgprs),
                    opt(s.spilled_vgprs),
                    opt(s.spilled_sgprs),
                    kib(s.scratch_bytes),
                    kib(s.code_bytes),
                    kib(s.lds_bytes),
                );
            }
        }
    }
    out
}

/// `s` as a JSON string.
fn json_str(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out += "\\\"",
            '\\' => out += "\\\\",
            c if (c as u32) < 0x20 => out += &format!("\\u{:04x}", c as u32),
            c => out.push(c),
        }
    }
    out + "\""
}

fn json_num(v: Option<u32>) -> String {
    v.map_or("null".to_string(), |v| v.to_string())
}

/// The rows as a JSON array of objects, one line each.
pub fn json(m: &Measurement) -> String {
    let mut lines = Vec::new();
    for row in rows(m) {
        let k = row.kernel;
        let mut o = format!(
            "{{\"device\": {}, \"family\": {}, \"scene\": {}, \"entry\": {}, \"dispatched\": {}, \"traversal\": {}, \"features\": {}, \"kernel\": {}, \"spirv_sha256\": {}, \"wave_requested\": {}",
            json_str(&m.device),
            m.family.map_or("null".into(), |f| json_str(f.name)),
            json_str(row.scene),
            json_str(k.entry.name()),
            row.dispatched,
            k.traversal,
            json_str(&k.features.to_string()),
            json_str(&k.kernel.to_string()),
            json_str(&k.digest),
            match row.compiled.wave {
                Wave::Default => "\"default\"".to_string(),
                Wave::Required(n) => n.to_string(),
            },
        );
        match &row.compiled.stats {
            Err(e) => o += &format!(", \"error\": {}}}", json_str(e)),
            Ok(s) => {
                let (waves, max) = row
                    .waves(m)
                    .map_or((None, None), |(w, m)| (Some(w), Some(m)));
                let breaks: Vec<String> = row.breaks().iter().map(|b| json_str(b)).collect();
                o += &format!(
                    ", \"wave\": {}, \"vgprs\": {}, \"sgprs\": {}, \"spilled_vgprs\": {}, \"spilled_sgprs\": {}, \"scratch_bytes\": {}, \"code_bytes\": {}, \"lds_bytes\": {}, \"instructions\": {}, \"waves_per_simd\": {}, \"max_waves_per_simd\": {}, \"budget_breaks\": [{}]}}",
                    s.wave,
                    json_num(s.vgprs),
                    json_num(s.sgprs),
                    json_num(s.spilled_vgprs),
                    json_num(s.spilled_sgprs),
                    json_num(s.scratch_bytes),
                    json_num(s.code_bytes),
                    json_num(s.lds_bytes),
                    json_num(s.instructions),
                    json_num(waves),
                    json_num(max),
                    breaks.join(", ")
                );
            }
        }
        lines.push(o);
    }
    format!("[\n{}\n]\n", lines.join(",\n"))
}

/// The rows that break a budget, as a table of what breaks which budget (empty: none).
pub fn budget_report(m: &Measurement) -> String {
    let mut out = String::new();
    for row in rows(m) {
        let breaks = row.breaks();
        if !breaks.is_empty() {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} |",
                row.scene,
                row.kernel.entry.name(),
                wave_label(row.compiled),
                breaks.join("; ")
            );
        }
    }
    if out.is_empty() {
        return out;
    }
    "| scene | entry | wave | breaks |\n| --- | --- | --- | --- |\n".to_string() + &out
}
