//! What a WGSL module of one's own (`glint kernels --wgsl FILE`) may hold before it
//! reaches naga: naga's parser, validator and SPIR-V writer recurse once per nesting
//! level of an expression, so a 3 000-term sum on one line, or 3 000 nested
//! parentheses, overflows the main thread's stack and aborts glint. A module is refused,
//! naming its file and line, when one statement holds more operators, or brackets nest
//! deeper, than any real kernel does (glint's own kernels stay under a tenth of each).

/// Largest WGSL file read (glint's own assembled kernels are under 300 KB).
pub const MAX_WGSL_BYTES: u64 = 4 << 20;
/// Most operator characters (`+ - * / % & | ^ < > ! ~ =`) in one statement.
pub const MAX_OPERATORS_PER_STATEMENT: usize = 512;
/// Deepest nesting of `(`, `[` and `{`.
pub const MAX_NESTING: usize = 64;

/// `text` if it is within the bounds above, else why not, starting with its line number
/// (`LINE: …`, for `FILE:LINE: …`).
pub fn check_bounds(text: &str) -> Result<(), String> {
    let bytes = text.as_bytes();
    let (mut line, mut depth, mut operators) = (1usize, 0usize, 0usize);
    let mut i = 0;
    while i < bytes.len() {
        let b = bytes[i];
        let next = bytes.get(i + 1).copied();
        match b {
            b'\n' => line += 1,
            b'/' if next == Some(b'/') => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'/' if next == Some(b'*') => {
                i = skip_block_comment(bytes, i, &mut line);
                continue;
            }
            b'(' | b'[' | b'{' => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Err(format!(
                        "{line}: brackets nest deeper than {MAX_NESTING} levels"
                    ));
                }
            }
            b')' | b']' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
        if matches!(b, b';' | b'{' | b'}') {
            operators = 0;
        } else if b"+-*/%&|^<>!~=".contains(&b) {
            operators += 1;
            if operators > MAX_OPERATORS_PER_STATEMENT {
                return Err(format!(
                    "{line}: a statement with more than {MAX_OPERATORS_PER_STATEMENT} operators (naga would overflow its stack)"
                ));
            }
        }
        i += 1;
    }
    Ok(())
}

/// The index just past the block comment opening at `start` (WGSL's nest), counting
/// its lines.
fn skip_block_comment(bytes: &[u8], start: usize, line: &mut usize) -> usize {
    let (mut i, mut open) = (start + 2, 1usize);
    while i < bytes.len() && open > 0 {
        match (bytes[i], bytes.get(i + 1).copied()) {
            (b'/', Some(b'*')) => {
                open += 1;
                i += 1;
            }
            (b'*', Some(b'/')) => {
                open -= 1;
                i += 1;
            }
            (b'\n', _) => *line += 1,
            _ => {}
        }
        i += 1;
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_sums_and_deep_nesting_are_refused_with_their_line() {
        let sum = format!("fn f() {{\n let y = {};\n}}", vec!["x"; 20_000].join(" + "));
        let e = check_bounds(&sum).unwrap_err();
        assert!(e.starts_with("2: ") && e.contains("operators"), "{e}");
        let nested = format!(
            "fn f() {{ let y = {}1{}; }}",
            "(".repeat(3000),
            ")".repeat(3000)
        );
        assert!(check_bounds(&nested).unwrap_err().contains("nest"));
        // Comments count for nothing.
        let comment = format!(
            "// {}\n/* {} /* {} */ */ fn f() {{}}",
            "-".repeat(5000),
            "+".repeat(900),
            "(".repeat(900)
        );
        assert_eq!(check_bounds(&comment), Ok(()));
    }

    /// Every kernel glint assembles passes, with room to spare.
    #[test]
    fn glint_s_own_kernels_are_well_within_the_bounds() {
        use glint::gpu::compile::kernel::KernelConfig;
        use glint::gpu::compile::shader::{assemble_with, Entry};
        use glint::pack::SceneFeatures;
        let every = SceneFeatures::ALL
            .iter()
            .fold(SceneFeatures(0), |all, (f, _)| SceneFeatures(all.0 | f.0));
        let wgsl = assemble_with(every, Entry::Render, KernelConfig::default());
        assert_eq!(check_bounds(&wgsl), Ok(()));
    }
}
