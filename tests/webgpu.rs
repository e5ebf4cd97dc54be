//! The kernels are portable WebGPU: naga validates every kernel in every
//! specialisation and tuning under a WebGPU device's capabilities and within
//! WebGPU's default limits, and Chromium's WebGPU (Tint, on SwiftShader)
//! compiles each kernel as `glint kernels --dump` writes it.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use glint_encoding::gpu_types::View;
use glint_encoding::primitive_kinds::ALL_KINDS;
use glint_encoding::specialization::Specialization;
use glint_gpu::kernel_dump::{self, KernelVariant};
use glint_gpu::shaders::{Kernel, ShaderSource};
use glint_gpu::Tuning;

/// What naga may accept for a kernel on a WebGPU device: core WebGPU, plus
/// subgroup operations for the kernels that need the `subgroups` feature.
fn webgpu_capabilities(tuning: Tuning) -> naga::valid::Capabilities {
    let features = if tuning.needs_subgroups() { wgpu::Features::SUBGROUP } else { wgpu::Features::empty() };
    wgpu_naga_bridge::features_to_naga_capabilities(features, wgpu::DownlevelFlags::compliant())
}

/// What of `module` exceeds WebGPU's default limits for a compute pipeline:
/// its workgroup size, and the bindings it declares (all of which its
/// pipeline layout holds) by kind, size and group.
fn beyond_default_limits(module: &naga::Module, entry_point: &str) -> Vec<String> {
    let limits = wgpu::Limits::default();
    let mut beyond = Vec::new();
    let entry = module.entry_points.iter().find(|e| e.name == entry_point).unwrap_or_else(|| panic!("no entry point {entry_point}"));
    let [x, y, z] = entry.workgroup_size;
    if x > limits.max_compute_workgroup_size_x || y > limits.max_compute_workgroup_size_y || z > limits.max_compute_workgroup_size_z {
        beyond.push(format!("workgroup size {x}x{y}x{z}"));
    }
    if x * y * z > limits.max_compute_invocations_per_workgroup {
        beyond.push(format!("max_compute_invocations_per_workgroup: {}", x * y * z));
    }
    let (mut storage, mut uniform, mut textures, mut workgroup_bytes) = (0, 0, 0, 0);
    for (_, global) in module.global_variables.iter() {
        let bytes = u64::from(module.types[global.ty].inner.size(module.to_ctx()));
        match global.space {
            naga::AddressSpace::Storage { .. } => storage += 1,
            naga::AddressSpace::Uniform => {
                uniform += 1;
                if bytes > u64::from(limits.max_uniform_buffer_binding_size) {
                    beyond.push(format!("max_uniform_buffer_binding_size: {:?} holds {bytes} bytes", global.name));
                }
            }
            naga::AddressSpace::Handle => textures += 1,
            naga::AddressSpace::WorkGroup => workgroup_bytes += bytes,
            _ => {}
        }
        if let Some(binding) = &global.binding
            && binding.group >= limits.max_bind_groups
        {
            beyond.push(format!("max_bind_groups: {:?} is in group {}", global.name, binding.group));
        }
    }
    for (limit, count, most) in [
        ("max_storage_buffers_per_shader_stage", storage, limits.max_storage_buffers_per_shader_stage),
        ("max_uniform_buffers_per_shader_stage", uniform, limits.max_uniform_buffers_per_shader_stage),
        ("max_sampled_textures_per_shader_stage", textures, limits.max_sampled_textures_per_shader_stage),
    ] {
        if count > most {
            beyond.push(format!("{limit}: {count} bindings"));
        }
    }
    if workgroup_bytes > u64::from(limits.max_compute_workgroup_storage_size) {
        beyond.push(format!("max_compute_workgroup_storage_size: {workgroup_bytes} bytes"));
    }
    beyond
}

fn assert_portable(kernel: Kernel, specialization: Specialization, tuning: Tuning) {
    let case = format!("{kernel:?} for {specialization}, tuned {}", tuning.name());
    let composed = ShaderSource::Embedded.compose(kernel, specialization, tuning).unwrap_or_else(|e| panic!("{case}: {e}"));
    let module = composed.validate_with(webgpu_capabilities(tuning)).unwrap_or_else(|e| panic!("{case}: {e}"));
    let beyond = beyond_default_limits(&module, kernel.entry_point());
    assert!(beyond.is_empty(), "{case} exceeds WebGPU's default limits: {}", beyond.join("; "));
}

#[test]
fn every_kernel_validates_under_webgpu_capabilities_and_default_limits() {
    for variant in KernelVariant::all() {
        assert_portable(variant.kernel, Specialization::ALL, variant.tuning);
    }
    let lavapipe = Tuning::LAVAPIPE;
    let kinds = (0..2 * (ALL_KINDS + 1)).map(|bits| {
        Specialization { kinds: bits & ALL_KINDS, secondary_rays: bits > ALL_KINDS, ..Specialization::ALL }
    });
    let views = View::ALL.map(|view| Specialization { view: Some(view), ..Specialization::ALL });
    for kernel in Kernel::ALL.into_iter().filter(|k| k.is_specialised()) {
        for specialization in kinds.clone().chain(views) {
            for tuning in [Tuning::PLAIN, lavapipe] {
                assert_portable(kernel, specialization, tuning.for_kernel(kernel));
            }
        }
    }
}

#[test]
fn the_dump_writes_each_kernel_variant_once_with_a_manifest() {
    let dir = tempfile::tempdir().unwrap();
    let written = kernel_dump::dump(&dir.path().join("kernels")).unwrap();
    let variants = KernelVariant::all();
    assert_eq!(written.len(), variants.len() + 1);
    for variant in &variants {
        let text = std::fs::read_to_string(dir.path().join("kernels").join(variant.file_name())).unwrap();
        assert_eq!(text, variant.webgpu_source().unwrap(), "{}", variant.file_name());
        assert_eq!(text.starts_with("enable subgroups;"), variant.tuning.needs_subgroups(), "{}", variant.file_name());
    }
    for kernel in Kernel::ALL {
        assert!(variants.iter().any(|v| v.kernel == kernel && v.tuning == Tuning::PLAIN.for_kernel(kernel)), "{kernel:?} has no plain variant");
    }
    assert!(variants.iter().any(|v| v.tuning.eye_tiles()), "no kernel walks eye tiles");
    let manifest: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.path().join("kernels").join(kernel_dump::DUMP_MANIFEST)).unwrap()).unwrap();
    assert_eq!(manifest.as_array().unwrap().len(), variants.len());
}

/// The page that compiles every dumped kernel in the browser's WebGPU and
/// logs a line per kernel ("GLINT ok NAME" or "GLINT rejected NAME: ..."),
/// then "GLINT done"; "GLINT failed ..." when WebGPU itself is missing.
const PAGE: &str = r#"<!doctype html><script>
const kernels = KERNELS;
(async () => {
  try {
    if (!navigator.gpu) throw new Error("navigator.gpu is missing: no WebGPU");
    const adapter = await navigator.gpu.requestAdapter();
    if (!adapter) throw new Error("no WebGPU adapter");
    const subgroups = adapter.features.has("subgroups");
    const device = await adapter.requestDevice({ requiredFeatures: subgroups ? ["subgroups"] : [] });
    for (const k of kernels) {
      if (k.subgroups && !subgroups) { console.log(`GLINT rejected ${k.file}: the adapter offers no subgroups`); continue; }
      device.pushErrorScope("validation");
      const module = device.createShaderModule({ code: k.source });
      const info = await module.getCompilationInfo();
      const errors = info.messages.filter(m => m.type === "error").map(m => `${m.lineNum}:${m.linePos} ${m.message}`);
      try {
        await device.createComputePipelineAsync({ layout: "auto", compute: { module, entryPoint: k.entry_point } });
      } catch (e) { errors.push(String(e.message || e)); }
      const scope = await device.popErrorScope();
      if (scope) errors.push(scope.message);
      console.log(errors.length ? `GLINT rejected ${k.file}: ${errors.join(" | ").replaceAll("\n", " ")}` : `GLINT ok ${k.file}`);
    }
  } catch (e) { console.log(`GLINT failed ${e.message || e}`); }
  console.log("GLINT done");
})();
</script>
"#;

/// How long Chromium may take to compile every kernel on a busy machine.
const CHROMIUM_TIMEOUT: Duration = Duration::from_secs(600);

/// The "GLINT ..." lines the page logs in headless Chromium, up to "GLINT
/// done"; panics when Chromium cannot start or `CHROMIUM_TIMEOUT` passes.
fn run_in_chromium(page: &Path) -> Vec<String> {
    let profile = tempfile::tempdir().unwrap();
    let mut chromium = Command::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.ci/chromium"))
        .args([
            "--headless=new",
            "--no-sandbox",
            "--enable-unsafe-webgpu",
            "--disable-gpu-sandbox",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--no-first-run",
            "--enable-logging=stderr",
            &format!("--user-data-dir={}", profile.path().display()),
            &format!("file://{}", page.display()),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("Chromium or Google Chrome runs (bash .ci/setup --tests installs Chromium)");
    let stderr = chromium.stderr.take().unwrap();
    let (send, lines) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            if let Some(at) = line.find("\"GLINT ") {
                let logged = line[at + 1..].split("\", source:").next().unwrap_or_default().to_string();
                if send.send(logged).is_err() {
                    break;
                }
            }
        }
    });
    let deadline = std::time::Instant::now() + CHROMIUM_TIMEOUT;
    let mut logged = Vec::new();
    let outcome = loop {
        match lines.recv_timeout(deadline.saturating_duration_since(std::time::Instant::now())) {
            Ok(line) if line == "GLINT done" => break Ok(()),
            Ok(line) => logged.push(line),
            Err(e) => break Err(e),
        }
    };
    let _ = chromium.kill();
    let _ = chromium.wait();
    if let Err(e) = outcome {
        panic!("Chromium did not finish the kernels within {CHROMIUM_TIMEOUT:?} ({e}); it logged: {logged:#?}");
    }
    logged
}

#[test]
fn every_kernel_compiles_in_chromiums_webgpu() {
    let dir = tempfile::tempdir().unwrap();
    let kernels = dir.path().join("kernels");
    kernel_dump::dump(&kernels).unwrap();
    let manifest: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(kernels.join(kernel_dump::DUMP_MANIFEST)).unwrap()).unwrap();
    let mut entries = manifest.as_array().unwrap().clone();
    for entry in &mut entries {
        let source = std::fs::read_to_string(kernels.join(entry["file"].as_str().unwrap())).unwrap();
        entry["source"] = source.into();
    }
    let page = dir.path().join("compile.html");
    // `</` never occurs in WGSL, so the JSON cannot end the script early.
    std::fs::write(&page, PAGE.replace("KERNELS", &serde_json::Value::from(entries.clone()).to_string())).unwrap();
    let logged = run_in_chromium(&page);
    let failed: Vec<&String> = logged.iter().filter(|l| !l.starts_with("GLINT ok ")).collect();
    assert!(failed.is_empty(), "Chromium's WebGPU rejected kernels:\n{}", failed.iter().map(|l| l.as_str()).collect::<Vec<_>>().join("\n"));
    for entry in &entries {
        let ok = format!("GLINT ok {}", entry["file"].as_str().unwrap());
        assert!(logged.contains(&ok), "no word on {}: {logged:#?}", entry["file"]);
    }
}
