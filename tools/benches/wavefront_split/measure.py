#!/usr/bin/env python3
"""Registers of a wavefront split's kernels, measured on RADV's null device.

The measurement tool of docs/journal/2026-12-02-wavefront-split-measured.md. For each
render-module `main` kernel that `glint kernels --spirv-dir DIR` wrote (a scene's
specialised module: the constants prelude, then `// ---- shaders/NAME ----` sections), it
re-assembles the module from this tree's shaders/ with the same features, for each
mailbox choice (`--mailboxes`, default `mb,last`: the hardware variant's slots, the
software variant's last-item slot; `off`: none), appends
tools/benches/wavefront_split/split.wgsl (the prototype kernels) and writes, for each prototype,
a module in which it is the entry `main` (the megakernel renamed away; `main` itself is
measured too). Then it runs `glint kernels --wgsl ... --format json` on them (RADV's
compiler, the render module's layout), keeps OUT/kernels.json and prints one table row
per (module, kernel): VGPRs per wave size and mailbox choice, code size, waves per SIMD
and the NAVI21 budgets' verdict.

    glint kernels SCENE... --entry main --wave 32 --spirv-dir /tmp/split/base
    tools/benches/wavefront_split/measure.py /tmp/split/base /tmp/split/out [--glint BIN]
        [--only split_closest,split_any] [--mailboxes mb,last,off] [--drop mesh]
    tools/benches/wavefront_split/measure.py - /tmp/split/out --report   # the table again

`--drop FEATURE,...` resolves features as absent: a what-if (what the kernels cost
without that feature's code), not a module any scene would get. The re-assembly with the
dump's own flags must give the dump back byte for byte (checked: the script stops
otherwise), so the `// #if` resolution here is glint's (src/gpu/compile/shader.rs::
preprocess_with). tests/gpu/kernel_instrument.rs keeps split.wgsl valid. About 2.5 s of
one core a kernel and wave size.
"""

import argparse
import json
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[3]
SPLIT = ROOT / "benches" / "wavefront_split" / "split.wgsl"
CANDIDATES = [
    "main",
    "split_camera",
    "split_closest",
    "split_closest_surface",
    "split_any",
    "split_transmittance",
    "split_shade",
]
SECTION = re.compile(r"^\n// ---- shaders/(\S+) ----\n", re.M)


def condition(text, names):
    negate = text.startswith("!")
    if negate:
        text = text[1:]
    hit = any(n.strip() in names for n in text.split("|"))
    return hit != negate


def preprocess(text, names):
    """glint's `// #if` resolution (src/gpu/compile/shader.rs::preprocess_with)."""
    stack = []
    out = []
    for line in text.splitlines():
        active = all(on and parent for on, parent, _ in stack[-1:]) if stack else True
        d = line.strip()
        if d.startswith("// #if "):
            stack.append([condition(d[7:].strip(), names), active, False])
        elif d == "// #else":
            stack[-1][0] = not stack[-1][0]
            stack[-1][2] = True
        elif d == "// #endif":
            stack.pop()
        elif d.startswith("// #"):
            raise ValueError(f"unknown directive {d}")
        elif active:
            out.append(line + "\n")
    assert not stack, "unclosed #if"
    return "".join(out)


def names_of(header):
    m = re.search(r"// Specialised for features: (.*); kernel: (.*)\n", header)
    features = {f.upper().replace("-", "_") for f in m.group(1).split()}
    kernel = m.group(2)
    flags = set()
    if "ray lists in storage" in kernel:
        flags.add("LISTS_IN_STORAGE")
    if "storage-texture tables" in kernel:
        flags.add("STORAGE_TABLES")
    if "iteration guard" in kernel:
        flags.add("ITERATION_GUARD")
    # (CAMERA_RAY_IN_LOOP as glint sets it: src/gpu/compile/shader.rs::KERNEL_FLAGS.)
    if "REFRACTION" in features or ("camera ray in loop" in kernel and "REFLECTION" in features):
        flags.add("CAMERA_RAY_IN_LOOP")
    if "any hit in one loop" in kernel:
        flags.add("ANY_HIT_ONE_LOOP")
    if "last-item mailbox" in kernel:
        flags.add("LAST_ITEM_MAILBOX")
    elif "mailboxes" in kernel:
        flags.add("MAILBOXES")
    return m.group(1), features, flags


def assemble(dump, names):
    parts = SECTION.split(dump)
    out = parts[0]
    for name, _ in zip(parts[1::2], parts[2::2]):
        out += f"\n// ---- shaders/{name} ----\n"
        out += preprocess((ROOT / "shaders" / name).read_text(), names)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dumps")
    ap.add_argument("out")
    ap.add_argument("--glint", default=str(ROOT / "target" / "debug" / "glint"))
    ap.add_argument("--family", default="NAVI21")
    ap.add_argument("--only", help="comma-separated candidates")
    ap.add_argument("--mailboxes", default="mb,last",
                    help="comma-separated: mb (every slot, the hardware variant's), last "
                    "(the last-item slot, the software variant's), off (none)")
    ap.add_argument("--report", action="store_true", help="only print OUT/kernels.json's table")
    ap.add_argument("--drop", default="", help="comma-separated features to resolve as absent "
                    "(what-if: the kernels' code without them; the scene would not render)")
    a = ap.parse_args()
    if a.report:
        report(json.loads((pathlib.Path(a.out) / "kernels.json").read_text()))
        return
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    wanted = a.only.split(",") if a.only else CANDIDATES
    files = []
    for dump_path in sorted(pathlib.Path(a.dumps).glob("main-*.wgsl")):
        dump = dump_path.read_text()
        feature_text, features, flags = names_of(SECTION.split(dump)[0])
        if assemble(dump, features | flags) != dump:
            sys.exit(f"{dump_path}: re-assembly differs from the dump (shaders/ changed?)")
        tag = "-".join(sorted(f.lower() for f in features - {"GRID"}))
        drop = {f.strip().upper().replace("-", "_") for f in a.drop.split(",") if f.strip()}
        if drop & features:
            tag += "+without-" + "-".join(sorted(f.lower() for f in drop & features))
        features = features - drop
        for mb in a.mailboxes.split(","):
            mailbox = {"mb": {"MAILBOXES"}, "last": {"LAST_ITEM_MAILBOX"}, "off": set()}[mb]
            names = (features | flags) - {"MAILBOXES", "LAST_ITEM_MAILBOX"} | mailbox
            module = assemble(dump, names)
            module += "\n// ---- tools/benches/wavefront_split/split.wgsl ----\n"
            module += preprocess(SPLIT.read_text(), names)
            for cand in wanted:
                if f"fn {cand}(" not in module:
                    continue
                text = module
                if cand != "main":
                    text = text.replace("fn main(", "fn megakernel_main(")
                    text = text.replace(f"fn {cand}(", "fn main(")
                path = out / f"{tag}--{mb}--{cand}.wgsl"
                path.write_text(text)
                files.append(path)
        print(f"{dump_path.name}: {feature_text}", file=sys.stderr)
    cmd = [a.glint, "kernels", "--family", a.family, "--wave", "32", "--wave", "64"]
    cmd += ["--format", "json"]
    for f in files:
        cmd += ["--wgsl", str(f)]
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode not in (0, 7):
        sys.exit(result.stderr)
    (out / "kernels.json").write_text(result.stdout)
    report(json.loads(result.stdout))


# The scenes of the journal entry, by the feature tag of their module.
SCENES = {
    "sphere": "simple",
    "cube-mesh-sphere": "nonhier, macho-cows",
    "cube-mesh-reflection-sphere": "demo",
    "cube-cylinder-refraction-sphere-torus": "glass",
    "cone-csg-cube-cylinder-refraction-sphere-torus": "csg",
    "bump-cone-cube-cylinder-mesh-sphere-texture-torus": "textures",
    "area_light-bump-csg-cube-cylinder-mesh-reflection-refraction-texture-torus": "scrabble",
}


def cell(r):
    if r is None:
        return "—"
    s = f"{r['vgprs']}"
    if r["spilled_vgprs"] or r["spilled_sgprs"]:
        s += f" sp {r['spilled_vgprs']}/{r['spilled_sgprs']}"
    if r["scratch_bytes"]:
        s += f" scr {r['scratch_bytes']}"
    return s


def report(data):
    """One row per (module, candidate): VGPRs (spilled VGPRs / SGPRs, scratch bytes where
    any) in wave32 and wave64 for each mailbox choice measured, the wave32 code size and
    waves per SIMD, and the verdict of the NAVI21 budgets (src/bin/glint/kernels/budget.rs: in
    wave32 traversal ≤ 96 VGPRs, others ≤ 128; in both sizes nothing spilled, no
    scratch)."""
    rows = {}
    for r in data:
        if "vgprs" not in r:
            continue
        tag, mb, cand = pathlib.Path(r["scene"]).stem.split("--")
        rows.setdefault((tag, cand), {})[(mb, r["wave"])] = r
    boxes = [b for b in ["mb", "last", "off"] if any((b, 32) in v for v in rows.values())]

    def scenes_of(tag):
        base, _, without = tag.partition("+")
        return SCENES.get(base, base) + (f" ({without})" if without else "")

    def verdict(v, b):
        measured = [v[(b, w)] for w in (32, 64) if (b, w) in v]
        if not measured:
            return "—"
        return "no" if any(r["budget_breaks"] for r in measured) else "ok"

    head = ["scenes", "kernel"] + [f"{b} w{w}" for b in boxes for w in (32, 64)]
    head += [f"code w32 ({boxes[0]})", "waves/SIMD w32 " + " / ".join(boxes),
             "budgets " + " / ".join(boxes)]
    print("| " + " | ".join(head) + " |")
    print("| --- | --- |" + " ---: |" * (2 * len(boxes) + 1) + " --- | --- |")
    order = {c: i for i, c in enumerate(CANDIDATES)}
    for (tag, cand), v in sorted(rows.items(), key=lambda kv: (kv[0][0], order[kv[0][1]])):
        cells = [scenes_of(tag), cand + (" (traversal)" if any(r["traversal"] for r in v.values()) else "")]
        cells += [cell(v.get((b, w))) for b in boxes for w in (32, 64)]
        first = v.get((boxes[0], 32))
        cells.append(f"{first['code_bytes'] / 1024:.1f} KiB" if first else "—")
        cells.append(" / ".join(str(v[(b, 32)]["waves_per_simd"]) if (b, 32) in v else "—" for b in boxes))
        cells.append(" / ".join(verdict(v, b) for b in boxes))
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
