//! Parts of an image rendered apart (`--region`, `--shard`) and stitched
//! (`glint stitch`): the same bytes as one render, in every format, also when
//! the shards run as concurrent processes (docs/scale-out.md); and parts that
//! do not make one image give one-line errors and no output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn glint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint")).args(args).output().expect("glint runs")
}

fn showcase() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/showcase.toml").to_str().unwrap().to_string()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn path(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Renders the showcase at 61 × 37 to `out` with `extra` options, checking it succeeds.
fn render(out: &Path, extra: &[&str]) {
    let scene = showcase();
    let mut args = vec!["render", &scene, "-o", path(out), "--width", "61", "--height", "37", "-q"];
    args.extend_from_slice(extra);
    let o = glint(&args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
}

fn stitch(parts: &[PathBuf], out: &Path) -> Output {
    stitch_with(parts, out, &[])
}

fn stitch_with(parts: &[PathBuf], out: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["stitch".to_string()];
    args.extend(parts.iter().map(|p| path(p).to_string()));
    args.extend(["-o".to_string(), path(out).to_string()]);
    args.extend(extra.iter().map(|a| a.to_string()));
    Command::new(env!("CARGO_BIN_EXE_glint")).args(&args).output().expect("glint runs")
}

/// Shards `indices` of `count` of the 61 × 37 showcase, rendered into `dir`.
fn shards(dir: &Path, indices: &[u32], count: u32) -> Vec<PathBuf> {
    indices
        .iter()
        .map(|i| {
            let part = dir.join(format!("shard{i}of{count}.png"));
            render(&part, &["--shard", &format!("{i}/{count}")]);
            part
        })
        .collect()
}

#[track_caller]
fn assert_same_file(a: &Path, b: &Path) {
    assert!(std::fs::read(a).unwrap() == std::fs::read(b).unwrap(), "{} and {} differ", a.display(), b.display());
}

#[test]
fn stitched_shards_are_the_single_render_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str]); 8] = [
        ("png", &["--spp", "4", "--filter", "tent", "--seed", "5"]),
        ("png", &["--bits", "16", "--spp", "2"]),
        ("ppm", &["--spp", "2"]),
        ("ppm", &["--bits", "16", "--plain"]),
        ("exr", &["--spp", "3"]),
        ("pfm", &[]),
        ("exr", &["--view", "depth"]),
        ("pfm", &["--view", "id"]),
    ];
    for (case, (ext, options)) in cases.iter().enumerate() {
        let whole = dir.path().join(format!("whole{case}.{ext}"));
        render(&whole, options);
        let parts: Vec<PathBuf> = (0..4)
            .map(|i| {
                let part = dir.path().join(format!("case{case}_shard{i}.{ext}"));
                let shard = format!("{i}/4");
                render(&part, &[*options, &["--shard", &shard][..]].concat());
                part
            })
            .collect();
        let stitched = dir.path().join(format!("stitched{case}.{ext}"));
        let o = stitch(&parts.iter().rev().cloned().collect::<Vec<_>>(), &stitched);
        assert!(o.status.success(), "case {case}: {}", stderr(&o));
        assert_same_file(&whole, &stitched);
    }
}

#[test]
fn regions_and_their_aovs_stitch_into_the_single_render() {
    let dir = tempfile::tempdir().unwrap();
    let whole = dir.path().join("whole.png");
    let whole_depth = dir.path().join("whole_depth.pfm");
    render(&whole, &["--spp", "2", "--aov", &format!("depth={}", path(&whole_depth))]);
    // Three regions of different shapes that cover the image once.
    let regions = [["0", "0", "20", "30"], ["20", "0", "61", "30"], ["0", "30", "61", "37"]];
    let (mut parts, mut depths) = (Vec::new(), Vec::new());
    for (i, region) in regions.iter().enumerate() {
        let (part, depth) = (dir.path().join(format!("r{i}.png")), dir.path().join(format!("r{i}_depth.pfm")));
        let aov = format!("depth={}", path(&depth));
        render(&part, &[&["--spp", "2", "--aov", &aov, "--region"][..], &region[..]].concat());
        let placement = std::fs::read_to_string(dir.path().join(format!("r{i}_depth.pfm.json"))).unwrap();
        assert!(placement.contains("\"image\": [61, 37]"), "{placement}");
        parts.push(part);
        depths.push(depth);
    }
    for (parts, want) in [(parts, whole), (depths, whole_depth)] {
        let stitched = dir.path().join(format!("stitched_{}", want.file_name().unwrap().to_str().unwrap()));
        let o = stitch(&parts, &stitched);
        assert!(o.status.success(), "{}", stderr(&o));
        assert_same_file(&want, &stitched);
    }
}

/// Tiles as small as a device too small for the image would need give the
/// files, AOVs and legend of an untiled render: tiles of 50 pixels are
/// narrower than the 61-pixel rows, tiles of 250 four whole rows.
#[test]
fn tiny_tiles_give_the_files_of_an_untiled_render() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str]); 4] = [
        ("png", &["--spp", "3", "--filter", "tent", "--seed", "2"]),
        ("png", &["--bits", "16", "--view", "heatmap"]),
        ("exr", &["--spp", "2"]),
        ("pfm", &["--view", "depth"]),
    ];
    let scene = showcase();
    for (case, (ext, options)) in cases.iter().enumerate() {
        let files = |name: &str| (dir.path().join(format!("{name}{case}.{ext}")), dir.path().join(format!("{name}{case}_depth.exr")));
        let run = |out: &Path, depth: &Path, tiles: &[&str]| {
            let aov = format!("depth={}", path(depth));
            let mut args = vec!["render", &scene, "-o", path(out), "--width", "61", "--height", "37", "--aov", &aov];
            args.extend_from_slice(options);
            args.extend_from_slice(tiles);
            let o = glint(&args);
            assert!(o.status.success(), "{args:?}: {}", stderr(&o));
            // The legend, when the view has one; the line before it has the time.
            stderr(&o).lines().skip(1).collect::<Vec<_>>().join("\n")
        };
        let (untiled, untiled_depth) = files("untiled");
        let legend = run(&untiled, &untiled_depth, &[]);
        for tile in ["50", "250"] {
            let (tiled, tiled_depth) = files(&format!("tiles{tile}_"));
            assert_eq!(run(&tiled, &tiled_depth, &["--max-tile-pixels", tile]), legend, "case {case}, tiles of {tile}");
            assert_same_file(&untiled, &tiled);
            assert_same_file(&untiled_depth, &tiled_depth);
        }
    }
}

/// What docs/scale-out.md does on a cluster, on this machine: N processes,
/// each rendering its shard at the same time, then one stitch.
#[test]
fn concurrent_shard_processes_stitch_into_the_single_process_render() {
    let dir = tempfile::tempdir().unwrap();
    let scene = showcase();
    let size = ["--width", "96", "--height", "64", "--spp", "2", "-q"];
    let whole = dir.path().join("whole.png");
    let o = glint(&[&["render", &scene, "-o", path(&whole)][..], &size].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    const SHARDS: u32 = 4;
    let parts: Vec<PathBuf> = (0..SHARDS).map(|i| dir.path().join(format!("shard_{i}.png"))).collect();
    let running: Vec<_> = parts
        .iter()
        .enumerate()
        .map(|(i, part)| {
            let shard = format!("{i}/{SHARDS}");
            Command::new(env!("CARGO_BIN_EXE_glint"))
                .args([&["render", &scene, "-o", path(part), "--shard", &shard][..], &size].concat())
                .spawn()
                .expect("glint starts")
        })
        .collect();
    for mut process in running {
        assert!(process.wait().unwrap().success());
    }
    let stitched = dir.path().join("stitched.png");
    let o = stitch(&parts, &stitched);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_same_file(&whole, &stitched);
}

#[test]
fn parts_that_do_not_make_one_image_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let part = |name: &str, extra: &[&str]| {
        let p = dir.path().join(name);
        render(&p, extra);
        p
    };
    let top = part("top.png", &["--shard", "0/2"]);
    let bottom = part("bottom.png", &["--shard", "1/2"]);
    let bottom16 = part("bottom16.png", &["--shard", "1/2", "--bits", "16"]);
    let bottom_exr = part("bottom.exr", &["--shard", "1/2"]);
    let top_ppm = part("top.ppm", &["--shard", "0/2"]);
    let bottom_plain = part("bottom_plain.ppm", &["--shard", "1/2", "--plain"]);
    let wider = dir.path().join("wider.png");
    let o = glint(&["render", &showcase(), "-o", path(&wider), "--width", "62", "--height", "37", "--shard", "1/2", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let overlapping = part("overlapping.png", &["--region", "0", "10", "61", "37"]);
    let whole = part("whole.png", &[]);
    let resized = dir.path().join("resized.png");
    std::fs::copy(&top, &resized).unwrap();
    std::fs::copy(dir.path().join("bottom.png.json"), dir.path().join("resized.png.json")).unwrap();
    let garbled = dir.path().join("garbled.png");
    std::fs::copy(&top, &garbled).unwrap();
    std::fs::write(dir.path().join("garbled.png.json"), "{\"image\": [61], \"region\": [0, 0, 61, 18]}").unwrap();

    // An unmatched shell glob reaches glint as it is.
    let unmatched = dir.path().join("shard_*.png");
    let cases: [(&[&PathBuf], &str, &str); 13] = [
        (&[&top], "out.png", "uncovered, the first at (0, 18): shard 1 of 2 is missing"),
        (&[&top, &bottom, &overlapping], "out.png", "overlap"),
        (&[&top, &wider], "out.png", "is a part of a 62x37 image, but"),
        (&[&top, &bottom16], "out.png", "is a 16-bit PNG, but"),
        (&[&top, &bottom_exr], "out.png", "is an RGB EXR, but"),
        (&[&top_ppm, &bottom], "out.ppm", "bottom.png: is an 8-bit PNG, but"),
        (&[&top_ppm, &bottom_plain], "out.ppm", "is an 8-bit plain PPM (P3), but"),
        (&[&top_ppm], "out.png", "the parts are .ppm files and stitching keeps their format: name the output .ppm"),
        (&[&top, &bottom], "out.exr", "the parts are .png files"),
        (&[&top, &whole], "out.png", "whole.png: no placement file"),
        (&[&resized, &bottom], "out.png", "is 61x18, but its placement"),
        (&[&garbled, &bottom], "out.png", "`image` must be a list of 2 whole numbers"),
        (&[&unmatched], "out.png", "shard_*.png: no such file"),
    ];
    for (parts, out, want) in cases {
        let out = dir.path().join(out);
        let o = stitch(&parts.iter().map(|p| p.to_path_buf()).collect::<Vec<_>>(), &out);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(3), "{want}: {err}");
        assert!(err.starts_with("glint: ") && err.contains(want) && err.lines().count() == 1, "want `{want}`, got: {err}");
        assert!(!out.exists(), "{want}: an output was written");
    }
}

#[test]
fn stitch_says_what_it_wrote_unless_quiet() {
    let dir = tempfile::tempdir().unwrap();
    let parts = shards(dir.path(), &[0, 1, 2], 3);
    let out = dir.path().join("full.png");
    let o = stitch(&parts, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), format!("glint: stitched 61x37 from 3 parts -> {}\n", path(&out)));
    let quiet = dir.path().join("quiet.png");
    let o = stitch_with(&parts, &quiet, &["-q"]);
    assert!(o.status.success() && o.stderr.is_empty(), "{}", stderr(&o));
    assert_same_file(&out, &quiet);
}

/// A shard records its I/N beside it, so that a stitch short of shards names
/// them and the Slurm `--array` that renders just them; parts written before
/// Glint recorded it still stitch.
#[test]
fn missing_shards_are_named_and_parts_without_a_shard_still_stitch() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("full.png");
    let parts = shards(dir.path(), &[0, 4], 5);
    let placement = std::fs::read_to_string(dir.path().join("shard4of5.png.json")).unwrap();
    assert_eq!(placement, "{\"glint_part\": 1, \"image\": [61, 37], \"region\": [0, 29, 61, 37], \"shard\": [4, 5]}\n");
    let o = stitch(&parts, &out);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        "glint: the parts leave 1342 pixels of the 61x37 image uncovered, the first at (0, 7): \
         shards 1-3 of 5 are missing: render them again (in a Slurm job array, --array=1-3)\n"
    );
    assert!(!out.exists());

    // Shards 0 and 1 of 2 as an older Glint wrote them: no `shard`.
    let old = shards(dir.path(), &[0, 1], 2);
    for (part, region) in old.iter().zip(["[0, 0, 61, 18]", "[0, 18, 61, 37]"]) {
        let text = format!("{{\"glint_part\": 1, \"image\": [61, 37], \"region\": {region}}}\n");
        std::fs::write(dir.path().join(format!("{}.json", part.file_name().unwrap().to_str().unwrap())), text).unwrap();
    }
    let o = stitch(&old[..1], &out);
    assert!(stderr(&o).ends_with("the first at (0, 18): a part is missing\n"), "{}", stderr(&o));
    let o = stitch(&old, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let whole = dir.path().join("whole.png");
    render(&whole, &[]);
    assert_same_file(&whole, &out);

    // A shard's `I/N` must be the region it holds.
    std::fs::write(dir.path().join("shard0of2.png.json"), "{\"image\": [61, 37], \"region\": [0, 0, 61, 18], \"shard\": [1, 2]}").unwrap();
    let o = stitch(&old, &out);
    assert!(stderr(&o).contains("shard0of2.png.json: the region 0 0 61 18 is not shard 1/2 of the 61x37 image"), "{}", stderr(&o));
}

#[test]
fn bad_regions_and_shards_are_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let scene = showcase();
    let size = ["--width", "61", "--height", "37"];
    for (extra, want) in [
        (&["--region", "0", "0", "62", "10"][..], "--region 0 0 62 10: must be X0 < X1 <= 61 and Y0 < Y1 <= 37"),
        (&["--region", "5", "5", "5", "10"], "inside the 61x37 image"),
        (&["--shard", "4/4"], "I must be below N (0/4 to 3/4)"),
        (&["--shard", "0/0"], "must be at least 1"),
        (&["--shard", "half"], "is not I/N"),
        (&["--shard", "0/38"], "has only 37 rows, so it splits into at most 37 shards"),
    ] {
        let o = glint(&[&["render", &scene, "-o", path(&out)][..], &size, extra].concat());
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {}", stderr(&o));
        assert!(stderr(&o).starts_with("glint: ") && stderr(&o).contains(want), "{extra:?}: {}", stderr(&o));
        assert!(!out.exists());
    }
}
