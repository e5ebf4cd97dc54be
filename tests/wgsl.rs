//! WGSL checks that need no device: every kernel parses and validates with naga,
//! and every struct the host uploads has the layout of its WGSL twin.

use std::mem::{offset_of, size_of};

use std::collections::{BTreeMap, BTreeSet};

use glint_encoding::gpu_bvh::{GpuGrid, GpuNode};
use glint_encoding::gpu_types::{
    DispatchParams, GpuCamera, GpuLight, GpuMaterial, GpuPrim, ProbeHeader, ProbeRay, ResolveParams, SceneUniforms, View,
};
use glint_encoding::primitive_kinds::{ALL_KINDS, KINDS};
use glint_encoding::specialization::Specialization;
use glint_gpu::shaders::{expand, imports, Kernel, ShaderSource, KERNEL_STAND_INS, SOURCES};
use glint_gpu::{Tuning, WorkgroupSizes, STAND_INS};

fn module(kernel: Kernel) -> naga::Module {
    ShaderSource::Embedded.compose(kernel, Specialization::ALL, Tuning::PLAIN).unwrap().validate().unwrap()
}

fn trace_module() -> naga::Module {
    module(Kernel::Trace)
}

#[test]
fn every_kernel_validates_in_every_tuning() {
    for kernel in Kernel::ALL {
        for tuning in Tuning::all() {
            if let Err(e) = ShaderSource::Embedded.compose(kernel, Specialization::ALL, tuning).unwrap().validate() {
                panic!("{kernel:?} tuned {}: {e}", tuning.name());
            }
        }
    }
}

/// The plain tuning, which every device but lavapipe gets, composes the
/// lecture's files alone: nothing of shaders/fast/.
#[test]
fn the_plain_tuning_composes_no_fast_file() {
    for kernel in Kernel::ALL {
        let composed = ShaderSource::Embedded.compose(kernel, Specialization::ALL, Tuning::PLAIN).unwrap();
        let fast: Vec<&String> = composed.files.iter().map(|(name, ..)| name).filter(|name| name.starts_with("fast/")).collect();
        assert!(fast.is_empty(), "{kernel:?}: {fast:?}");
    }
}

/// Every kernel that intersects primitives validates for every specialisation
/// a scene can need, plain and tuned as lavapipe's, and only those kernels are
/// compiled per scene.
#[test]
fn every_specialisation_validates() {
    let lavapipe = Tuning::LAVAPIPE.with_eye_tiles(false);
    for kernel in Kernel::ALL {
        let composed = ShaderSource::Embedded.compose(kernel, Specialization::ALL, Tuning::PLAIN).unwrap();
        let intersects = composed.files.iter().any(|(name, ..)| name == "lib/primitive.wgsl");
        assert_eq!(kernel.is_specialised(), intersects, "{kernel:?}");
        if !intersects {
            continue;
        }
        let views = View::ALL.map(|view| Specialization { view: Some(view), ..Specialization::ALL });
        let kinds = (0..2 * (ALL_KINDS + 1)).map(|bits| {
            Specialization { kinds: bits & ALL_KINDS, secondary_rays: bits > ALL_KINDS, ..Specialization::ALL }
        });
        let plain = Specialization {
            smooth_triangles: false,
            refractions: false,
            highlights: false,
            checker: false,
            attenuation: false,
            tinted_shadows: false,
            depth_cue: false,
            ..Specialization::ALL
        };
        for specialization in kinds.chain(views).chain([plain]) {
            for tuning in [Tuning::PLAIN, lavapipe, lavapipe.with_eye_tiles(true)] {
                if let Err(e) = ShaderSource::Embedded.compose(kernel, specialization, tuning.for_kernel(kernel)).unwrap().validate() {
                    panic!("{kernel:?} for {specialization}, tuned {}: {e}", tuning.name());
                }
            }
        }
    }
}

/// The host dispatches as many workgroups as the kernels' `@workgroup_size`
/// (times the pixels an invocation traces) needs to cover a band, in every
/// profile's workgroup sizes.
#[test]
fn workgroup_sizes_are_the_hosts() {
    for workgroups in [WorkgroupSizes::PLAIN, WorkgroupSizes::LAVAPIPE] {
        let tuning = Tuning::PLAIN.with_workgroups(workgroups);
        for kernel in [Kernel::Trace, Kernel::Primary, Kernel::Diffuse] {
            let module = ShaderSource::Embedded.compose(kernel, Specialization::ALL, tuning).unwrap().validate().unwrap();
            let entry = module.entry_points.iter().find(|e| e.name == kernel.entry_point()).unwrap();
            let [x, y] = tuning.workgroup_size(kernel);
            assert_eq!(entry.workgroup_size, [x, y, 1], "{kernel:?}, {workgroups:?}");
        }
    }
}

/// The functions `block` calls.
fn callees(block: &naga::Block) -> Vec<naga::Handle<naga::Function>> {
    block
        .iter()
        .flat_map(|statement| match statement {
            naga::Statement::Call { function, .. } => vec![*function],
            naga::Statement::Block(b) => callees(b),
            naga::Statement::If { accept, reject, .. } => [callees(accept), callees(reject)].concat(),
            naga::Statement::Switch { cases, .. } => cases.iter().flat_map(|c| callees(&c.body)).collect(),
            naga::Statement::Loop { body, continuing, .. } => [callees(body), callees(continuing)].concat(),
            _ => Vec::new(),
        })
        .collect()
}

/// The places that call the function named `name` in `module`'s entry point
/// and the functions it reaches, which are all a driver compiles.
fn call_sites(module: &naga::Module, name: &str) -> usize {
    let mut reached = Vec::new();
    let mut calls = callees(&module.entry_points[0].function.body);
    let mut sites = 0;
    while let Some(function) = calls.pop() {
        sites += usize::from(module.functions[function].name.as_deref() == Some(name));
        if !reached.contains(&function) {
            reached.push(function);
            calls.extend(callees(&module.functions[function].body));
        }
    }
    sites
}

/// lavapipe inlines every call, so each call of the BVH walk is a copy of the
/// walk and its primitive tests in the compiled kernel, which a cold start
/// pays for. Tuned for it, the ray tree traces its rays and their shadow rays
/// through one call; the plain tree calls the walk for its rays (`trace_step`)
/// and for shadow rays (`cast_shadow_ray`). The walk tests a leaf's
/// primitives through one call.
#[test]
fn the_ray_tree_walks_the_bvh_through_one_call() {
    for kernel in [Kernel::Trace, Kernel::Probe] {
        for (one_walk_tree, walks) in [(true, 1), (false, 2)] {
            let tuning = Tuning::PLAIN.with_one_walk_tree(one_walk_tree);
            let module = ShaderSource::Embedded.compose(kernel, Specialization::ALL, tuning).unwrap().validate().unwrap();
            assert_eq!(call_sites(&module, "traverse"), walks, "{kernel:?}, one walk {one_walk_tree}");
            assert_eq!(call_sites(&module, "intersect_prim"), 1, "{kernel:?}");
        }
    }
}

/// The WGSL files under `dir`, at any depth, named relative to `shaders/`.
fn wgsl_files_under(dir: &std::path::Path, found: &mut BTreeSet<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            wgsl_files_under(&path, found);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            let name = path.strip_prefix(ShaderSource::source_dir()).unwrap().to_str().unwrap().replace('\\', "/");
            found.insert(name);
        }
    }
}

/// `shaders/` holds exactly the embedded files, each reached by some kernel.
#[test]
fn every_shader_file_is_embedded_and_part_of_a_kernel() {
    let mut on_disk = BTreeSet::new();
    wgsl_files_under(&ShaderSource::source_dir(), &mut on_disk);
    assert_eq!(on_disk, SOURCES.iter().map(|s| s.to_string()).collect::<BTreeSet<_>>(), "shaders/ and the embedded files differ");
    let used: BTreeSet<String> = Kernel::ALL
        .iter()
        .flat_map(|&k| Tuning::all().into_iter().map(move |tuning| ShaderSource::Embedded.compose(k, Specialization::ALL, tuning).unwrap()))
        .flat_map(|composed| composed.files.into_iter().map(|(name, ..)| name))
        .collect();
    for name in SOURCES {
        assert!(used.contains(*name), "shaders/{name} is in no kernel");
    }
}

/// The names a WGSL file declares at module scope.
fn declarations(source: &str) -> Vec<String> {
    let name = |rest: &str| rest.split(|c: char| !(c.is_alphanumeric() || c == '_')).next().unwrap_or_default().to_string();
    source
        .lines()
        .filter_map(|line| {
            if let Some(rest) = ["fn ", "struct ", "const "].iter().find_map(|k| line.strip_prefix(k)) {
                return Some(name(rest));
            }
            // `var name`, `var<private> name`, `@group(0) @binding(1) var<storage, read> name`.
            let var = line.find("var")?;
            let after = &line[var + 3..];
            let after = if after.starts_with('<') { &after[after.find('>')? + 1..] } else { after };
            (line.starts_with("var") || line.starts_with('@')).then(|| name(after.trim_start()))
        })
        .filter(|name| !name.is_empty())
        .collect()
}

/// Imports are stated, not inherited, and none is idle: a file uses a name
/// declared in another file only if it imports that file, and it uses
/// something of every file it imports. A fast/ file that stands in for a
/// lib/ file, or a kernel's own file that stands in for one in that kernel
/// (the probe's notes), declares the functions other files use of it, and an
/// import of the lib/ file stands for it too. The primary kernel carries no
/// ray tree.
#[test]
fn imports_are_exactly_what_each_file_uses() {
    let read = |name: &str| expand(&std::fs::read_to_string(ShaderSource::source_dir().join(name)).unwrap()).unwrap();
    let functions = |file: &str| -> BTreeSet<String> {
        let source = read(file);
        declarations(&source).into_iter().filter(|n| source.contains(&format!("fn {n}("))).collect()
    };
    let stand_ins: Vec<(&str, &str)> =
        STAND_INS.iter().map(|s| (s.plain, s.fast)).chain(KERNEL_STAND_INS.iter().map(|s| (s.plain, s.own))).collect();
    let plain_of = |name: &str| stand_ins.iter().find(|(_, stand_in)| *stand_in == name).map(|(plain, _)| *plain);
    // The names a file's code uses, members after a `.` left out.
    let words = |source: &str| -> BTreeSet<String> {
        let code: String = source.lines().map(|l| l.split("//").next().unwrap_or_default()).collect::<Vec<_>>().join("\n");
        let mut words = BTreeSet::new();
        let mut rest = code.as_str();
        while let Some(start) = rest.find(|c: char| c.is_alphanumeric() || c == '_') {
            let len = rest[start..].find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len() - start);
            if !rest[..start].ends_with('.') {
                words.insert(rest[start..start + len].to_string());
            }
            rest = &rest[start + len..];
        }
        words
    };
    // A stand-in declares every function of its file that other files use.
    for &(plain, stand_in) in &stand_ins {
        let others: BTreeSet<String> =
            SOURCES.iter().filter(|n| **n != plain && plain_of(n) != Some(plain)).flat_map(|n| words(&read(n))).collect();
        let missing: Vec<String> = functions(plain).difference(&functions(stand_in)).filter(|f| others.contains(*f)).cloned().collect();
        assert!(missing.is_empty(), "shaders/{stand_in} stands in for {plain} without {missing:?}");
    }
    // A stand-in's own names are what it declares beyond the file it stands in for.
    let declared: BTreeMap<String, Vec<String>> = SOURCES
        .iter()
        .filter(|n| !Kernel::ALL.iter().any(|k| k.file() == **n))
        .map(|n| {
            let plain: Vec<String> = plain_of(n).map(|p| declarations(&read(p))).unwrap_or_default();
            (n.to_string(), declarations(&read(n)).into_iter().filter(|d| !plain.contains(d)).collect())
        })
        .collect();
    for name in SOURCES {
        let raw = std::fs::read_to_string(ShaderSource::source_dir().join(name)).unwrap();
        let (used, imported) = (words(&read(name)), imports(&raw));
        for (file, names) in &declared {
            if file == name || plain_of(name) == Some(file.as_str()) {
                continue;
            }
            let uses = names.iter().any(|n| used.contains(n));
            assert_eq!(uses, imported.contains(file), "shaders/{name}: {} {file}", if uses { "uses but does not import" } else { "imports but does not use" });
        }
    }
    let primary = ShaderSource::Embedded.compose(Kernel::Primary, Specialization::ALL, Tuning::PLAIN).unwrap();
    assert!(!primary.source.contains("fn trace_pixel"), "the primary kernel carries the ray tree");
    assert!(!primary.source.contains("fn diffuse_only"), "the primary kernel carries shadow rays");
}

/// The ray tree's notes record nothing but in the probe kernel, which
/// composes its own in their place, in every tuning; each kernel's stand-in
/// stands in for a lib/ file that some other kernel composes.
#[test]
fn only_the_probe_kernel_records_the_ray_tree() {
    for kernel in Kernel::ALL {
        for tuning in Tuning::all() {
            let files: Vec<String> = ShaderSource::Embedded.compose(kernel, Specialization::ALL, tuning).unwrap().files.into_iter().map(|(name, ..)| name).collect();
            let has = |file: &str| files.iter().any(|name| name == file);
            assert!(!(has("lib/notes.wgsl") && has("kernels/probe_notes.wgsl")), "{kernel:?} tuned {}: {files:?}", tuning.name());
            if kernel == Kernel::Probe {
                assert!(has("kernels/probe_notes.wgsl"), "{files:?}");
            } else {
                assert!(!has("kernels/probe_notes.wgsl"), "{kernel:?}: {files:?}");
            }
        }
    }
    assert!(ShaderSource::Embedded.compose(Kernel::Trace, Specialization::ALL, Tuning::PLAIN).unwrap().files.iter().any(|(name, ..)| name == "lib/notes.wgsl"));
    for s in KERNEL_STAND_INS {
        assert!(s.plain.starts_with("lib/") && s.own.starts_with("kernels/"), "{s:?}");
        assert_eq!(s.kernel.file_for(s.plain), s.own);
        assert!(Kernel::ALL.iter().any(|k| k.file_for(s.plain) == s.plain), "no kernel composes {}", s.plain);
    }
}

/// The words of a SIMD machine's lanes, of drivers and of lavapipe's tuning,
/// which the lecture's files leave to shaders/fast/ and docs/decisions/.
const TUNING_WORDS: [&str; 8] = ["lane", "lanes", "simd", "driver", "lavapipe", "llvm", "packet", "packets"];

/// The files of ARCHITECTURE.md's table of lecture concepts hold the code as
/// the lecture reads it, one ray at a time: no four-wide twin (`fn …4(`) and
/// no word of lanes, drivers or lavapipe.
#[test]
fn concept_files_hold_the_one_ray_code() {
    let architecture = std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("ARCHITECTURE.md")).unwrap();
    let table = architecture.split("## Where each lecture concept lives").nth(1).and_then(|s| s.split("\n## ").next()).unwrap();
    let files: BTreeSet<String> = table
        .lines()
        .filter_map(|row| row.strip_prefix('|')?.split('|').nth(1))
        .flat_map(|cell| cell.split('`').skip(1).step_by(2).filter(|name| name.ends_with(".wgsl")).map(|name| format!("lib/{name}")).collect::<Vec<_>>())
        .collect();
    for concept in ["camera", "sphere", "triangle", "polygon", "cone", "plane", "shade", "shadow", "reflect", "refract", "ray_tree", "bvh"] {
        assert!(files.contains(&format!("lib/{concept}.wgsl")), "ARCHITECTURE.md's concept table lacks {concept}.wgsl: {files:?}");
    }
    for file in &files {
        assert!(SOURCES.contains(&file.as_str()), "ARCHITECTURE.md names shaders/{file}, which is not embedded");
        let source = std::fs::read_to_string(ShaderSource::source_dir().join(file)).unwrap();
        for (i, line) in source.lines().enumerate() {
            let four_wide = line.split("fn ").skip(1).any(|rest| rest.split('(').next().is_some_and(|name| name.ends_with('4')));
            assert!(!four_wide, "shaders/{file}:{}: a four-wide function belongs in shaders/fast/: {line}", i + 1);
            let lower = line.to_lowercase();
            let word = lower.split(|c: char| !c.is_alphanumeric()).find(|w| TUNING_WORDS.contains(w));
            assert!(word.is_none(), "shaders/{file}:{}: \"{}\" belongs in shaders/fast/ or docs/decisions/: {line}", i + 1, word.unwrap_or_default());
        }
    }
}

#[test]
fn errors_name_the_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    for name in SOURCES {
        let to = dir.path().join(name);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        std::fs::copy(ShaderSource::source_dir().join(name), to).unwrap();
    }
    let compose = || ShaderSource::Dir(dir.path().into()).compose(Kernel::Trace, Specialization::ALL, Tuning::PLAIN);
    // An unknown name in `file`'s first line containing `code`, which validation finds at that line.
    let break_name = |file: &str, code: &str| {
        let path = dir.path().join(file);
        let broken = std::fs::read_to_string(&path).unwrap().replacen(code, &format!("{code} undefined_name +"), 1);
        std::fs::write(&path, &broken).unwrap();
        let line = broken.lines().position(|l| l.contains("undefined_name")).unwrap() + 1;
        let err = compose().unwrap().validate().unwrap_err().to_string();
        assert!(err.contains(&format!("shaders/{file}:{line}")), "{err}");
        std::fs::copy(ShaderSource::source_dir().join(file), path).unwrap();
    };
    break_name("lib/sphere.wgsl", "let b =");
    // Past a generated piece, lines are still the file's own.
    break_name("lib/primitive.wgsl", "let m =");

    std::fs::write(dir.path().join("lib/sphere.wgsl"), "// A sphere.\n// import: types nowhere\n").unwrap();
    let err = compose().unwrap_err().to_string();
    assert!(err.contains("shaders/lib/sphere.wgsl:2: imports lib/nowhere.wgsl, which is no shader file"), "{err}");
    std::fs::copy(ShaderSource::source_dir().join("lib/sphere.wgsl"), dir.path().join("lib/sphere.wgsl")).unwrap();
    std::fs::write(dir.path().join("lib/primitive.wgsl"), "// generated: intersect_disk\n").unwrap();
    let err = compose().unwrap_err().to_string();
    assert!(err.contains("shaders/lib/primitive.wgsl:1: no generated piece intersect_disk"), "{err}");
}

/// Every line of a composed kernel is the line `locate` names: a file's own,
/// or one of the generated dispatch. Every kind's file is embedded.
#[test]
fn each_composed_line_is_the_line_it_is_located_at() {
    for kernel in Kernel::ALL {
        let composed = ShaderSource::Embedded.compose(kernel, Specialization::ALL, Tuning::PLAIN).unwrap();
        let mut generated = 0;
        for (i, line) in composed.source.lines().enumerate() {
            let place = composed.locate(i + 1);
            let Some((file, number)) = place.strip_prefix("shaders/").and_then(|p| p.rsplit_once(':')) else {
                generated += usize::from(place.starts_with("the generated dispatch"));
                continue;
            };
            let text = std::fs::read_to_string(ShaderSource::source_dir().join(file)).unwrap();
            assert_eq!(text.lines().nth(number.parse::<usize>().unwrap() - 1), Some(line), "{kernel:?} line {}: {place}", i + 1);
        }
        let pieces: usize = composed.files.iter().filter(|(name, ..)| name.starts_with("the generated dispatch")).count();
        assert_eq!(pieces > 0, generated > 0, "{kernel:?}");
    }
    for kind in KINDS {
        assert!(SOURCES.contains(&kind.file), "{} is not embedded", kind.file);
    }
}

/// Asserts the WGSL struct `name` has exactly the given members at the host's
/// offsets and the host's size.
fn check_layout(module: &naga::Module, name: &str, size: usize, members: &[(&str, usize)]) {
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no WGSL struct {name}"));
    let naga::TypeInner::Struct { members: wgsl_members, span } = &ty.inner else {
        panic!("{name} is not a struct");
    };
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    assert_eq!(*span as usize, size, "{name}: WGSL size {span} vs host {size}");
    assert_eq!(layouter[handle].size as usize, size, "{name}");
    let wgsl: Vec<(String, usize)> =
        wgsl_members.iter().map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize)).collect();
    let host: Vec<(String, usize)> = members.iter().map(|(n, o)| (n.to_string(), *o)).collect();
    assert_eq!(wgsl, host, "{name}: members and offsets differ");
}

macro_rules! layout {
    ($module:expr, $ty:ident { $($field:ident),* $(,)? }) => {
        check_layout(&$module, stringify!($ty), size_of::<$ty>(), &[$((stringify!($field), offset_of!($ty, $field))),*])
    };
}

#[test]
fn host_structs_match_wgsl() {
    let m = trace_module();
    layout!(m, GpuCamera { eye, projection, u, half_width, v, half_height, w, _pad });
    layout!(
        m,
        SceneUniforms {
            camera, background, width, ambient, height, depth_cue_color, light_count, depth_cue, max_depth, cutoff,
            flags, bvh_root, plane_first, plane_count, _pad0, _pad1
        }
    );
    layout!(m, DispatchParams { origin, end, sample_index, seed, sample_count, pixel_filter, view, tile_x, tile_y, tile_width });
    layout!(m, GpuLight { position, kind, radiance, attenuation, coefficients });
    layout!(
        m,
        GpuMaterial {
            color, ka, specular_color, kd, reflect, ks, transmit, shininess, f0, ior, checker, checker_size, flags, _pad0,
            _pad1, _pad2
        }
    );
    layout!(m, GpuPrim { a, b, c, kind_material, object, first, count });
    layout!(m, GpuNode { quantized, children });
    layout!(m, GpuGrid { origin, exponents });
    let probe = module(Kernel::Probe);
    layout!(
        probe,
        ProbeRay {
            origin, kind, dir, parent, weight, depth, point, t, geometric, object, shading, flags, ambient, eta, diffuse,
            n_dot_l, specular, distance, transmittance, light, cue_scale, material, blocker, _pad
        }
    );
    // The buffer's rays start right after the head the host reads.
    let (_, buffer) = probe.types.iter().find(|(_, t)| t.name.as_deref() == Some("ProbeBuffer")).unwrap();
    let naga::TypeInner::Struct { members, .. } = &buffer.inner else { panic!("ProbeBuffer is not a struct") };
    assert_eq!(members.last().unwrap().offset as usize, size_of::<ProbeHeader>());
    for kernel in [Kernel::Resolve, Kernel::Present] {
        let m = module(kernel);
        layout!(m, ResolveParams { pixel_count, tone_map, exposure, view, scale, _pad0, _pad1, _pad2 });
    }
}

/// The constants host and kernels share reach every kernel from Rust, with
/// Rust's values; no shader file declares one of them again.
#[test]
fn shared_constants_come_from_the_host() {
    use glint_encoding::gpu_types as g;
    let module = trace_module();
    let value = |name: &str| {
        let (_, c) = module.constants.iter().find(|(_, c)| c.name.as_deref() == Some(name)).unwrap_or_else(|| panic!("no WGSL constant {name}"));
        match module.global_expressions[c.init] {
            naga::Expression::Literal(naga::Literal::U32(v)) => f64::from(v),
            naga::Expression::Literal(naga::Literal::F32(v)) => f64::from(v),
            ref e => panic!("{name} = {e:?}"),
        }
    };
    for (name, host) in [
        ("PRIM_POLYGON", f64::from(g::PRIM_POLYGON)),
        ("VIEW_HEATMAP", f64::from(g::VIEW_HEATMAP)),
        ("MAX_DEPTH", f64::from(glint_scene::MAX_DEPTH_LIMIT)),
        ("BVH_STACK", glint_scene::bvh::MAX_DEPTH as f64),
        ("LEAF", f64::from(g::LEAF)),
        ("MISS", f64::from(g::MISS)),
        ("STAT_COUNT", f64::from(g::STAT_COUNT)),
    ] {
        assert_eq!(value(name), host, "{name}");
    }
    let prelude = g::wgsl_prelude();
    let shared: Vec<&str> = prelude.lines().filter_map(|l| l.strip_prefix("const ")?.split(':').next()).collect();
    for file in SOURCES {
        let text = std::fs::read_to_string(ShaderSource::source_dir().join(file)).unwrap();
        for name in &shared {
            assert!(!text.contains(&format!("const {name}:")), "shaders/{file} declares the shared constant {name} again");
        }
    }
}
