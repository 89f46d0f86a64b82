//! Tiers 1 and 2 of GPU parity (no GPU needed): the WGSL struct twins have the same
//! member names, order, offsets and sizes as the Rust Pod structs (asked of naga), and
//! every shader specialisation parses and validates.

use glint::gpu::compile::shader::{
    all_feature_sets, assemble, assemble_with, preprocess, validate, Entry,
};
use glint::gpu::upload::buffers::GpuTile;
use glint::gpu::{KernelConfig, KernelVariant};
use glint::mailboxes::Mailboxes;
use glint::pack::{
    PackedGlobals, PackedInstance, PackedLight, PackedMaterial, PackedMesh, PackedTriangle,
    PackedTriangleNormals, PackedTriangleUv, SceneFeatures,
};
use glint::testing::probe::{ProbeRay, ProbeResult};
use std::mem::{offset_of, size_of};

/// (name, offset) of each listed field of a Rust struct, in the order given.
macro_rules! rust_fields {
    ($t:ty { $($f:ident),* $(,)? }) => {
        (stringify!($t), size_of::<$t>(), vec![$((stringify!($f), offset_of!($t, $f))),*])
    };
}

fn check_struct(module: &naga::Module, (name, size, fields): (&str, usize, Vec<(&str, usize)>)) {
    let ty = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("WGSL has no struct {name}"))
        .1;
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        panic!("WGSL {name} is not a struct");
    };
    let wgsl: Vec<(String, usize)> = members
        .iter()
        .map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize))
        .collect();
    let rust: Vec<(String, usize)> = fields.iter().map(|(n, o)| (n.to_string(), *o)).collect();
    assert_eq!(
        wgsl, rust,
        "{name}: WGSL members (left) vs Rust fields (right)"
    );
    assert_eq!(*span as usize, size, "{name}: WGSL span vs Rust size_of");
}

fn module(entry: Entry) -> naga::Module {
    let all = SceneFeatures(SceneFeatures::ALL.iter().fold(0, |m, (f, _)| m | f.0));
    let source = assemble(all, entry);
    validate(&source, all).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn wgsl_structs_match_rust_layout() {
    let render = module(Entry::Render);
    let all = SceneFeatures(SceneFeatures::ALL.iter().fold(0, |m, (f, _)| m | f.0));
    check_struct(
        &render,
        rust_fields!(PackedInstance {
            world_to_object,
            object_to_world,
            kind,
            material,
            params
        }),
    );
    check_struct(&render, rust_fields!(PackedTriangle { p0, p1, p2 }));
    check_struct(&render, rust_fields!(PackedTriangleUv { uv0, uv1, uv2 }));
    check_struct(&render, rust_fields!(PackedTriangleNormals { n0, n1, n2 }));
    check_struct(
        &render,
        rust_fields!(PackedMesh {
            grid_min,
            first_cell,
            grid_max,
            first_triangle,
            grid_cell_size,
            num_triangles,
            grid_dims,
            _pad0
        }),
    );
    check_struct(
        &render,
        rust_fields!(PackedMaterial {
            kd,
            shininess,
            ks,
            flags,
            reflection,
            ior,
            diffuse_texture,
            specular_texture,
            bump_texture,
            bump_strength
        }),
    );
    check_struct(
        &render,
        rust_fields!(PackedLight {
            position,
            kind,
            colour,
            samples,
            falloff,
            _pad0,
            edge_u,
            _pad1,
            edge_v,
            _pad2
        }),
    );
    check_struct(
        &render,
        rust_fields!(PackedGlobals {
            eye,
            tan_half_fov,
            forward,
            aspect,
            right,
            width,
            up,
            height,
            ambient,
            num_lights,
            background_top,
            max_depth,
            background_bottom,
            min_weight,
            grid_min,
            num_instances,
            grid_cell_size,
            num_triangles,
            grid_dims,
            grid_enabled,
            grid_max,
            aa_mode,
            aa_samples,
            aa_threshold,
            aa_depth,
            camera_media_count,
            camera_media,
            debug_view,
            lens_radius,
            focus_distance,
            environment,
            environment_cos,
            environment_sin,
            _pad0,
            _pad1
        }),
    );
    // GpuTile's last field is the wavefront kernels' only: in modules with them (the
    // hardware variant's, glass or not) all of it, in the others (the software variant's)
    // the fields before it.
    let gpu_tile = rust_fields!(GpuTile {
        origin,
        size,
        side,
        level,
        items,
        sentinel,
        stratum,
        slice
    });
    check_struct(&render, gpu_tile.clone());
    let hardware_chains = SceneFeatures(all.0 & !SceneFeatures::REFRACTION.0);
    let chains = validate(&assemble(hardware_chains, Entry::Render), hardware_chains)
        .unwrap_or_else(|e| panic!("{e}"));
    check_struct(&chains, gpu_tile);
    let software = KernelConfig::for_variant(KernelVariant::Software, &wgpu::Limits::default());
    let software = validate(&assemble_with(all, Entry::Render, software), all)
        .unwrap_or_else(|e| panic!("{e}"));
    let (name, _, fields) = rust_fields!(GpuTile {
        origin,
        size,
        side,
        level,
        items,
        sentinel
    });
    check_struct(&software, (name, offset_of!(GpuTile, stratum), fields));
    let probe = module(Entry::Probe);
    check_struct(
        &probe,
        rust_fields!(ProbeRay {
            origin,
            t_max,
            dir,
            mode
        }),
    );
    check_struct(
        &probe,
        rust_fields!(ProbeResult {
            hit,
            t,
            item,
            part,
            normal,
            _pad1
        }),
    );
}

#[test]
fn every_specialisation_validates() {
    let sets = all_feature_sets();
    // None, all, each alone, all but each, each pair.
    let n = SceneFeatures::ALL.len();
    assert_eq!(sets.len(), 2 + 2 * n + n * (n - 1) / 2);
    let mut failures = Vec::new();
    for features in sets {
        // Every render kernel is in one module, so Render covers them all; each kernel
        // variant an adapter may choose (hardware: one mailbox slot, no guard, sampled
        // tables, per-ray lists in storage, the camera ray in the loop, the wavefront
        // kernels; software: one mailbox slot, the guard and storage-texture tables, the
        // megakernel `main`; a smaller workgroup where the adapter's limits ask
        // for it), and the variants with full mailboxes (`bench --gpu --mailboxes on`)
        // and without mailboxes the tests compare them with (this one with the wavefront
        // kernels). The guard is in the render module only.
        let hardware = KernelConfig::default();
        let full = KernelConfig {
            mailboxes: Mailboxes::Full,
            ..hardware
        };
        let software = KernelConfig {
            mailboxes: Mailboxes::LastItem,
            iteration_guard: true,
            storage_tables: true,
            lists_in_storage: false,
            camera_ray_in_loop: false,
            any_hit_one_loop: false,
            wavefront: false,
            ..hardware
        };
        let small = KernelConfig {
            workgroup_side: 4,
            ..software
        };
        let bare = KernelConfig {
            mailboxes: Mailboxes::Off,
            wavefront: true,
            ..software
        };
        for (entry, kernel) in [
            (Entry::Render, hardware),
            (Entry::Render, full),
            (Entry::Render, software),
            (Entry::Render, small),
            (Entry::Render, bare),
            (Entry::Probe, hardware),
            (Entry::Probe, full),
            (Entry::Probe, software),
            (Entry::Probe, bare),
        ] {
            let source = assemble_with(features, entry, kernel);
            let side = format!("const WORKGROUP_SIZE: u32 = {}u;", kernel.workgroup_side);
            if let Err(e) = validate(&source, features) {
                failures.push(format!("[{features}] {entry:?} {kernel}:\n{e}"));
            } else if (entry.is_render() && kernel.iteration_guard)
                != source.contains("fn loop_limiter_tripped(")
            {
                failures.push(format!(
                    "[{features}] {entry:?}: guard {} not resolved",
                    kernel.iteration_guard
                ));
            } else if (kernel.mailboxes == Mailboxes::Full)
                != source.contains("(*mailbox).items[slot] = item;")
                || (kernel.mailboxes == Mailboxes::LastItem)
                    != source.contains("(*mailbox).last = item;")
            {
                failures.push(format!(
                    "[{features}] {entry:?}: {} not resolved",
                    kernel.mailboxes
                ));
            } else if kernel.lists_in_storage
                != source.contains("var<storage, read_write> ray_lists")
            {
                failures.push(format!(
                    "[{features}] {entry:?}: lists in storage {} not resolved",
                    kernel.lists_in_storage
                ));
            } else if !source.contains(&side) {
                failures.push(format!("[{features}] {entry:?}: no `{side}`"));
            }
        }
    }
    // Every entry point is in its module: the hardware variant's, or where that has not
    // the entry (`main`), the software variant's.
    let all = SceneFeatures(SceneFeatures::ALL.iter().fold(0, |m, (f, _)| m | f.0));
    // (The wavefront entries' validation is gpu_wavefront.rs's; the megakernel entries
    // they replace are only in the modules without them.)
    let megakernels = KernelConfig {
        wavefront: false,
        ..KernelConfig::default()
    };
    for entry in Entry::ALL.into_iter().filter(|e| !e.is_wavefront()) {
        let source = match entry.exists_in(KernelConfig::default(), all) {
            true => assemble(all, entry),
            false => assemble_with(all, entry, megakernels),
        };
        let module = validate(&source, all).unwrap();
        assert!(
            module.entry_points.iter().any(|e| e.name == entry.name()),
            "{entry:?}"
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Functions of absent features are not in the source naga sees.
#[test]
fn absent_features_are_compiled_out() {
    let spheres = SceneFeatures::SPHERE;
    let source = assemble(spheres, Entry::Render);
    let module = validate(&source, spheres).unwrap();
    let names: Vec<&str> = module
        .functions
        .iter()
        .filter_map(|(_, f)| f.name.as_deref())
        .collect();
    for absent in [
        "intersect_box",
        "intersect_triangle",
        "triangle_ray_setup",
        "dda_setup",
        "min_axis",
        "intersect_cylinder",
        "intersect_cone",
        "cylinder_surface",
        "cone_surface",
        "nearest_interval_end",
        "cylinder_cone_angle_u",
        "environment",
        "environment_uv",
        "sample_environment",
    ] {
        assert!(
            !source.contains(&format!("fn {absent}(")),
            "{absent} in the source"
        );
        assert!(!names.contains(&absent), "{absent} in the module");
    }
    for present in [
        "intersect_sphere",
        "closest_hit",
        "shade_phong",
        "trace_ray",
    ] {
        assert!(names.contains(&present), "{present} missing");
    }
    assert!(
        !source.contains("MATERIAL_REFLECTIVE) != 0u"),
        "reflection push present"
    );
    let with_all = assemble(
        SceneFeatures(
            SceneFeatures::CUBE.0
                | SceneFeatures::MESH.0
                | SceneFeatures::GRID.0
                | SceneFeatures::REFLECTION.0,
        ),
        Entry::Render,
    );
    for present in [
        "fn intersect_box(",
        "fn intersect_triangle(",
        "fn dda_setup(",
        "MATERIAL_REFLECTIVE) != 0u",
    ] {
        assert!(with_all.contains(present), "{present} missing");
    }
    assert!(!with_all.contains("fn intersect_sphere("));
    assert!(!with_all.contains("fn cylinder_surface("));
    // Cylinder and cone each bring their own functions and the shared ones, not the other's.
    for (feature, present, absent) in [
        (
            SceneFeatures::CYLINDER,
            "fn intersect_cylinder(",
            "fn intersect_cone(",
        ),
        (
            SceneFeatures::CONE,
            "fn intersect_cone(",
            "fn intersect_cylinder(",
        ),
    ] {
        let source = assemble(feature, Entry::Render);
        validate(&source, feature).unwrap();
        for shared in [present, "fn nearest_interval_end(", "fn instance_surface("] {
            assert!(source.contains(shared), "[{feature}] {shared} missing");
        }
        assert!(!source.contains(absent), "[{feature}] {absent} present");
    }
}

/// The torus code (src/tracer/geometry/torus.wgsl and its dispatch arms) is in exactly the
/// specialisations with TORUS, and every specialisation set includes TORUS.
#[test]
fn torus_code_only_with_torus() {
    let sets = all_feature_sets();
    assert!(sets.iter().any(|s| s.contains(SceneFeatures::TORUS)));
    let torus_code = [
        "fn intersect_torus(",
        "fn torus_surface(",
        "fn first_quartic_root(",
        "fn newton_bisect(",
        "fn poly_eval(",
        "== KIND_TORUS {",
    ];
    for features in sets {
        for entry in [Entry::Render, Entry::Probe] {
            let source = assemble(features, entry);
            for code in torus_code {
                assert_eq!(
                    source.contains(code),
                    features.contains(SceneFeatures::TORUS),
                    "[{features}] {entry:?}: {code}"
                );
            }
        }
    }
}

#[test]
fn preprocessor_directives() {
    let text = "a\n// #if SPHERE|CUBE\nb\n// #if !MESH\nc\n// #else\nd\n// #endif\n// #endif\ne\n";
    let out = preprocess("t", text, SceneFeatures::CUBE).unwrap();
    assert_eq!(out, "a\nb\nc\ne\n");
    let out = preprocess("t", text, SceneFeatures::MESH).unwrap();
    assert_eq!(out, "a\ne\n");
    let err = preprocess("t", "// #if TEAPOT\n// #endif\n", SceneFeatures::CUBE).unwrap_err();
    assert!(
        err.contains("unknown feature 'TEAPOT'") && err.contains("TORUS"),
        "{err}"
    );
    assert!(preprocess("t", "// #if CUBE\n", SceneFeatures::CUBE).is_err());
    assert!(preprocess("t", "// #endif\n", SceneFeatures::CUBE).is_err());
}

/// The preludes are the only source of constants: no WGSL file defines its own (the
/// tracer's, under src/, from src/constants.rs; the benchmark kernel's, in shaders/bench/,
/// from src/bench/).
#[test]
fn shaders_define_no_constants() {
    fn collect(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                collect(&path, out);
            } else if path.extension().is_some_and(|e| e == "wgsl") {
                out.push(path);
            }
        }
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    collect(&root.join("src"), &mut files);
    collect(&root.join("shaders"), &mut files);
    for expected in [
        "bench/torus.wgsl",
        "tracer/path/trace.wgsl",
        "pack/layout.wgsl",
    ] {
        assert!(files.iter().any(|p| p.ends_with(expected)), "{files:?}");
    }
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        for (i, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap().trim_start();
            assert!(
                !code.starts_with("const ") && !code.starts_with("override "),
                "{}:{}: constants belong in a prelude (src/constants.rs, src/bench/)",
                path.display(),
                i + 1
            );
        }
    }
}

/// The area-light code (shadow sampling in src/tracer/shading/shade.wgsl and src/tracer/base/rng.wgsl) is in
/// exactly the specialisations with AREA_LIGHT, which every_specialisation_validates
/// covers.
#[test]
fn area_light_code_only_with_area_lights() {
    let sets = all_feature_sets();
    assert!(sets.iter().any(|s| s.contains(SceneFeatures::AREA_LIGHT)));
    for features in sets {
        for entry in [Entry::Render, Entry::Probe] {
            let source = assemble(features, entry);
            for code in ["fn area_light(", "fn shadow_random(", "== LIGHT_AREA {"] {
                assert_eq!(
                    source.contains(code),
                    features.contains(SceneFeatures::AREA_LIGHT),
                    "[{features}] {entry:?}: {code}"
                );
            }
        }
    }
}

/// The dielectric code (src/tracer/shading/dielectric.wgsl, the transmitted push in trace.wgsl and
/// the shadow walk in shade.wgsl) is in exactly the specialisations with REFRACTION; the
/// others keep any_hit shadows.
#[test]
fn refraction_code_only_with_refraction() {
    let sets = all_feature_sets();
    assert!(sets.iter().any(|s| s.contains(SceneFeatures::REFRACTION)));
    for features in sets {
        for entry in [Entry::Render, Entry::Probe] {
            let source = assemble(features, entry);
            for code in [
                "fn dielectric_interface(",
                "fn refract_direction(",
                "fn schlick_reflectance(",
                "fn shadow_transmittance(",
                "fn medium_push(",
                "struct MediumStack",
                "(m.flags & MATERIAL_REFRACTIVE) != 0u",
                "shadow_transmittance(origin, position, s.magnitude)",
                "shading_media = entry.media;",
            ] {
                if entry == Entry::Probe && (code.starts_with("(m.") || code.starts_with("shading"))
                {
                    continue;
                }
                assert_eq!(
                    source.contains(code),
                    features.contains(SceneFeatures::REFRACTION),
                    "[{features}] {entry:?}: {code}"
                );
            }
        }
    }
}

/// Texture lookups (and the UV debug view, which pack turns TEXTURE on for) are compiled
/// only into scenes with textures; the shared texel, mip-level and UV code, and the ray
/// cone that picks the level, with textures or bump maps; bump mapping only with bump
/// maps.
#[test]
fn texture_and_bump_code_only_with_textures_and_bump_maps() {
    for features in all_feature_sets() {
        let texture = features.contains(SceneFeatures::TEXTURE);
        let bump = features.contains(SceneFeatures::BUMP);
        let mesh = features.contains(SceneFeatures::MESH);
        for entry in [Entry::Render, Entry::Probe] {
            let source = assemble(features, entry);
            let expect = [
                ("fn surface_colours(", texture),
                ("fn sample_texture(", texture || bump),
                ("fn texel(", texture || bump),
                ("load_triangle_uv(", mesh && (texture || bump)),
                ("fn triangle_frame(", mesh && (texture || bump)),
                ("fn bump_normal(", bump),
                ("fn height_gradient(", bump),
                ("fn filtered_height_gradient(", bump),
                ("fn sample_texture_filtered(", texture || bump),
                ("fn camera_cone(", texture || bump),
                (
                    ".cone = camera_cone(primary)",
                    (texture || bump) && entry == Entry::Render,
                ),
                ("cone: vec2<f32>,", texture || bump),
                ("shading_normal(shading, n)", bump && entry == Entry::Render),
                ("DEBUG_VIEW_UV {", texture && entry == Entry::Render),
            ];
            for (code, present) in expect {
                assert_eq!(
                    source.contains(code),
                    present,
                    "[{features}] {entry:?}: {code}"
                );
            }
        }
    }
}

/// Smooth shading (src/tracer/shading/smooth.wgsl, the triangle normals' loader, the interpolated
/// normal in shade_hit and the probe, smooth refraction with REFRACTION) is compiled only into scenes with the SMOOTH
/// feature (which packing sets only for meshes with vertex normals).
#[test]
fn smooth_code_only_with_smooth_meshes() {
    for features in all_feature_sets() {
        let smooth = features.contains(SceneFeatures::SMOOTH);
        let refraction = features.contains(SceneFeatures::REFRACTION);
        for entry in [Entry::Render, Entry::Probe] {
            let source = assemble(features, entry);
            let expect = [
                ("fn smooth_normal(", smooth),
                ("fn visible_normal(", smooth),
                ("fn load_triangle_normals(", smooth),
                ("smooth_normal(hit, s)", smooth),
                (
                    "visible_normal(n, facing, -ray.dir)",
                    smooth && entry == Entry::Render,
                ),
                ("fn smooth_interface(", smooth && refraction),
                (
                    "smooth_interface(ray.dir",
                    smooth && refraction && entry == Entry::Render,
                ),
            ];
            for (code, present) in expect {
                assert_eq!(
                    source.contains(code),
                    present,
                    "[{features}] {entry:?}: {code}"
                );
            }
        }
    }
}

/// The CSG code (src/tracer/geometry/csg.wgsl, the torus's interval search, the dispatch and surface
/// arms) is in exactly the specialisations with CSG (and some primitive kind for its
/// leaves), and absent from every other.
#[test]
fn csg_code_only_with_csg() {
    let sets = all_feature_sets();
    assert!(sets.iter().any(|s| s.contains(SceneFeatures::CSG)));
    let kinds = SceneFeatures::SPHERE.0
        | SceneFeatures::CUBE.0
        | SceneFeatures::CYLINDER.0
        | SceneFeatures::CONE.0
        | SceneFeatures::TORUS.0;
    let csg_code = [
        "fn intersect_csg(",
        "fn csg_evaluate(",
        "fn csg_combine(",
        "fn csg_push_leaf(",
        "fn leaf_intervals(",
        "fn csg_surface(",
        "fn csg_t_at(",
        "== KIND_CSG {",
    ];
    for features in sets {
        let with_csg = features.contains(SceneFeatures::CSG) && features.0 & kinds != 0;
        for entry in [Entry::Render, Entry::Probe] {
            let source = assemble(features, entry);
            for code in csg_code {
                assert_eq!(
                    source.contains(code),
                    with_csg,
                    "[{features}] {entry:?}: {code}"
                );
            }
            assert_eq!(
                source.contains("fn torus_intervals("),
                with_csg && features.contains(SceneFeatures::TORUS),
                "[{features}] {entry:?}: torus_intervals"
            );
        }
    }
    // And in naga's module, not only the source.
    let features = SceneFeatures(SceneFeatures::CSG.0 | SceneFeatures::SPHERE.0);
    let module = validate(&assemble(features, Entry::Render), features).unwrap();
    let names: Vec<&str> = module
        .functions
        .iter()
        .filter_map(|(_, f)| f.name.as_deref())
        .collect();
    assert!(names.contains(&"intersect_csg") && names.contains(&"csg_combine"));
    let module = validate(
        &assemble(SceneFeatures::SPHERE, Entry::Render),
        SceneFeatures::SPHERE,
    )
    .unwrap();
    assert!(!module
        .functions
        .iter()
        .any(|(_, f)| f.name.as_deref().is_some_and(|n| n.contains("csg"))));
    assert!(module
        .global_variables
        .iter()
        .all(|(_, g)| g.name.as_deref().is_none_or(|n| !n.starts_with("csg_t"))));
}

/// The render module's entry points are exactly those `Entry::exists_in` names, in both
/// kernel variants and for every feature set (what `glint kernels`, `--dump-kernels` and
/// the pipelines look up is what naga finds): in particular the hardware variant's module
/// has no megakernel `main`, whose AA none the wavefront kernels trace (glass too), and
/// the software variant's has it.
#[test]
fn render_entries_are_those_exists_in_names() {
    let limits = wgpu::Limits::default();
    for variant in [KernelVariant::Hardware, KernelVariant::Software] {
        let kernel = KernelConfig::for_variant(variant, &limits);
        for features in all_feature_sets() {
            let source = assemble_with(features, Entry::Render, kernel);
            let module = naga::front::wgsl::parse_str(&source)
                .unwrap_or_else(|e| panic!("[{features}] {variant:?}: {e}"));
            let mut found: Vec<&str> = module
                .entry_points
                .iter()
                .map(|e| e.name.as_str())
                .collect();
            found.sort_unstable();
            let mut named: Vec<&str> = Entry::ALL
                .into_iter()
                .filter(|e| e.is_render() && e.exists_in(kernel, features))
                .map(Entry::name)
                .collect();
            named.sort_unstable();
            assert_eq!(
                found, named,
                "[{features}] {variant:?}: in the module (left), exists_in (right)"
            );
            assert_eq!(
                found.contains(&"main"),
                variant == KernelVariant::Software,
                "[{features}] {variant:?}: `main`"
            );
        }
    }
}
