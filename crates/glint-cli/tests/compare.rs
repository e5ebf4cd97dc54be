//! `glint compare` end to end: metrics against values worked out by hand,
//! the worst pixel's position, the diff map, exit codes and one-line errors.
//! Needs no GPU.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn glint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint")).args(args).output().expect("glint runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn arg(path: &Path) -> &str {
    path.to_str().unwrap()
}

fn png(dir: &Path, name: &str, width: u32, height: u32, pixel: impl Fn(u32, u32) -> [u8; 3]) -> PathBuf {
    let path = dir.join(name);
    image::RgbImage::from_fn(width, height, |x, y| image::Rgb(pixel(x, y))).save(&path).unwrap();
    path
}

/// A colour PFM of linear values, rows given top first.
fn pfm(dir: &Path, name: &str, width: u32, pixels: &[[f32; 3]]) -> PathBuf {
    let height = pixels.len() as u32 / width;
    let mut bytes = format!("PF\n{width} {height}\n-1.0\n").into_bytes();
    for row in pixels.chunks(width as usize).rev() {
        for value in row.iter().flatten() {
            bytes.extend(value.to_le_bytes());
        }
    }
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// 16 × 12 pixels of one colour, and the same with pixel (11, 7) changed.
fn one_pixel_apart(dir: &Path) -> (PathBuf, PathBuf) {
    let a = png(dir, "a.png", 16, 12, |_, _| [90, 120, 150]);
    let b = png(dir, "b.png", 16, 12, |x, y| if (x, y) == (11, 7) { [250, 20, 20] } else { [90, 120, 150] });
    (a, b)
}

fn json(o: &Output) -> serde_json::Value {
    let text = stdout(o);
    assert_eq!(text.lines().count(), 1, "{text}");
    serde_json::from_str(&text).unwrap()
}

#[test]
fn identical_images_are_within_every_threshold() {
    let dir = tempfile::tempdir().unwrap();
    let a = png(dir.path(), "a.png", 16, 8, |x, y| [(x * 16) as u8, (y * 30) as u8, 200]);
    let b = png(dir.path(), "b.png", 16, 8, |x, y| [(x * 16) as u8, (y * 30) as u8, 200]);
    let o = glint(&["compare", arg(&a), arg(&b)]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = stdout(&o);
    for line in [
        "size         16x8",
        "flip         0 (threshold <= 0.01: pass)",
        "psnr         inf dB",
        "rmse         0",
        "max          0",
        "above 0.2    0 of 128 pixels (0%, at most 0.5%: pass)",
        "worst pixel  (0, 0), FLIP error 0",
        "within threshold",
    ] {
        assert!(text.lines().any(|l| l == line), "`{line}` missing in:\n{text}");
    }
    assert_eq!(stderr(&o), "");
    for metric in ["flip", "psnr", "rmse", "max"] {
        let o = glint(&["compare", arg(&a), arg(&b), "--metric", metric, "--json"]);
        assert_eq!(o.status.code(), Some(0), "{metric}: {}", stderr(&o));
        let v = json(&o);
        assert_eq!(v["pass"], true);
        assert!(v["psnr"].is_null(), "PSNR of identical images is infinite: {v}");
    }
}

#[test]
fn a_one_pixel_change_is_found_at_its_position() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = one_pixel_apart(dir.path());
    for metric in ["flip", "psnr", "rmse", "max"] {
        let o = glint(&["compare", arg(&a), arg(&b), "--metric", metric, "--json"]);
        let v = json(&o);
        assert_eq!((v["worst"]["x"].as_u64(), v["worst"]["y"].as_u64()), (Some(11), Some(7)), "{metric}: {v}");
        assert_eq!(v["metric"], metric);
    }
    // The mean FLIP of one pixel in 192 is small, but the pixel is far above 0.2,
    // and one pixel in 192 is more than 0.5 %.
    let o = glint(&["compare", arg(&a), arg(&b)]);
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    let text = stdout(&o);
    assert!(text.contains("worst pixel  (11, 7), FLIP error "), "{text}");
    assert_eq!(text.lines().last(), Some("not within threshold"));
    // A verdict is not an error: nothing on stderr.
    assert_eq!(stderr(&o), "");
    let v = json(&glint(&["compare", arg(&a), arg(&b), "--metric", "max", "--json"]));
    assert_eq!(v["pixels_above"], 1);
    assert_eq!(v["pass"], false);
    // sRGB 250 vs 90 in red: linear 0.9560 - 0.1022 = 0.8538.
    assert!((v["max"].as_f64().unwrap() - 0.8538).abs() < 1e-3, "{v}");
}

#[test]
fn each_metric_matches_values_worked_out_by_hand() {
    let dir = tempfile::tempdir().unwrap();
    // Linear channel differences: 0.1 | 0.2 | none | 0.4, so
    // MSE = (0.01 + 0.04 + 0.16) / 12 = 0.0175, RMSE = 0.132288,
    // PSNR = 10 log10(1 / 0.0175) = 17.5696 dB, max = 0.4.
    let a = pfm(dir.path(), "a.pfm", 2, &[[0.5, 0.5, 0.5], [0.1, 0.2, 0.3], [0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]);
    let b = pfm(dir.path(), "b.pfm", 2, &[[0.6, 0.5, 0.5], [0.1, 0.4, 0.3], [0.0, 0.0, 0.0], [0.6, 1.0, 1.0]]);
    let v = json(&glint(&["compare", arg(&a), arg(&b), "--metric", "max", "--json"]));
    assert!((v["rmse"].as_f64().unwrap() - 0.132_288).abs() < 1e-5, "{v}");
    assert!((v["psnr"].as_f64().unwrap() - 17.5696).abs() < 1e-3, "{v}");
    assert!((v["max"].as_f64().unwrap() - 0.4).abs() < 1e-6, "{v}");
    assert_eq!((v["worst"]["x"].as_u64(), v["worst"]["y"].as_u64()), (Some(1), Some(1)), "{v}");

    for (metric, threshold, code) in
        [("rmse", "0.14", 0), ("rmse", "0.13", 1), ("psnr", "17.5", 0), ("psnr", "17.6", 1), ("max", "0.4001", 0), ("max", "0.39", 1)]
    {
        let o = glint(&["compare", arg(&a), arg(&b), "--metric", metric, "--threshold", threshold]);
        assert_eq!(o.status.code(), Some(code), "{metric} {threshold}: {}", stdout(&o));
    }
    // The pixel tolerance counts pixels whose largest channel difference exceeds it.
    let v = json(&glint(&["compare", arg(&a), arg(&b), "--metric", "max", "--pixel-tolerance", "0.15", "--json"]));
    assert_eq!(v["pixels_above"], 2);
    assert_eq!(v["fraction_above"], 0.5);
    // FLIP of uniform black against uniform white, by hand (Andersson et al.
    // 2020): HyAB distance 100 in L*, 100^0.7 = 25.12, beyond p_c·c_max =
    // 16.51 of c_max = 41.27 (green to blue), so 0.95 + 8.61 / 24.76 · 0.05 = 0.967.
    let black = pfm(dir.path(), "black.pfm", 4, &[[0.0; 3]; 16]);
    let white = png(dir.path(), "white.png", 4, 4, |_, _| [255; 3]);
    let v = json(&glint(&["compare", arg(&black), arg(&white), "--json"]));
    assert!((v["flip"].as_f64().unwrap() - 0.967).abs() < 2e-3, "{v}");
}

#[test]
fn png_is_decoded_from_srgb_to_compare_with_linear_files() {
    let dir = tempfile::tempdir().unwrap();
    let grey = png(dir.path(), "grey.png", 3, 2, |_, _| [128; 3]);
    // sRGB 128 is 0.215861 in linear light.
    let linear = pfm(dir.path(), "grey.pfm", 3, &[[0.215_861; 3]; 6]);
    let o = glint(&["compare", arg(&grey), arg(&linear), "--metric", "max", "--threshold", "1e-5"]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    let exr = dir.path().join("grey.exr");
    let rgb = image::Rgb32FImage::from_pixel(3, 2, image::Rgb([0.215_861; 3]));
    image::DynamicImage::ImageRgb32F(rgb).save(&exr).unwrap();
    let o = glint(&["compare", arg(&exr), arg(&grey), "--metric", "max", "--threshold", "1e-5"]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
}

#[test]
fn the_diff_map_shows_the_error_where_it_is_with_a_legend() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = one_pixel_apart(dir.path());
    for metric in ["flip", "max"] {
        let diff = dir.path().join(format!("{metric}-diff.png"));
        let o = glint(&["compare", arg(&a), arg(&b), "--metric", metric, "--diff", arg(&diff)]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        let map = image::open(&diff).unwrap().to_rgb8();
        // At least 200 pixels wide for the legend, and a strip below the image.
        assert_eq!(map.width(), 200);
        assert!(map.height() > 12 + 20, "{}", map.height());
        let brightness = |x, y| map.get_pixel(x, y).0.iter().map(|&c| u32::from(c)).sum::<u32>();
        let brightest = (0..12).flat_map(|y| (0..16).map(move |x| (x, y))).max_by_key(|&(x, y)| brightness(x, y)).unwrap();
        assert_eq!(brightest, (11, 7), "{metric}");
        // The legend has a colour bar: many colours along one row.
        let bar_colours: std::collections::HashSet<_> = (0..200).map(|x| map.get_pixel(x, 12 + 18).0).collect();
        assert!(bar_colours.len() > 50, "{metric}: {} colours in the bar row", bar_colours.len());
    }
}

#[test]
fn bad_inputs_fail_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let small = png(dir.path(), "small.png", 2, 2, |_, _| [0; 3]);
    let big = png(dir.path(), "big.png", 4, 3, |_, _| [0; 3]);
    let garbage = dir.path().join("garbage.png");
    std::fs::write(&garbage, b"not a png").unwrap();
    let missing = dir.path().join("missing.exr");
    let bmp = dir.path().join("picture.bmp");
    let diff = dir.path().join("d.png");
    let cases: Vec<(Vec<&str>, i32, String)> = vec![
        (vec![arg(&small), arg(&big)], 3, format!("glint: {}: the image is 4x3, but the reference {} is 2x2", big.display(), small.display())),
        (vec![arg(&missing), arg(&big)], 3, format!("glint: {}: cannot read: ", missing.display())),
        (vec![arg(&small), arg(&garbage)], 3, format!("glint: {}: not a readable image", garbage.display())),
        (vec![arg(&small), arg(&bmp)], 3, format!("glint: {}: unsupported image format: use .png, .exr or .pfm", bmp.display())),
        (vec![arg(&small), arg(&small), "--metric", "ssim"], 2, "glint: invalid value 'ssim' for '--metric".into()),
        (vec![arg(&small), arg(&small), "--threshold", "nan"], 2, "`nan` is not a finite number".into()),
        (vec![arg(&small), arg(&small), "--max-bad-fraction", "2"], 2, "`2` is not a fraction in [0, 1]".into()),
        (vec![arg(&small), arg(&small), "--diff", "d.jpg"], 2, "d.jpg: the diff map is written as .png".into()),
        (vec![arg(&small), arg(&small), "--diff", "/no/such/dir/d.png"], 5, "glint: /no/such/dir/d.png: cannot write: ".into()),
        (vec![arg(&small), arg(&big), "--diff", arg(&diff)], 3, "the image is 4x3".into()),
    ];
    for (extra, code, needle) in cases {
        let mut args = vec!["compare"];
        args.extend(&extra);
        let o = glint(&args);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {}", stderr(&o));
        let err = stderr(&o);
        assert!(err.contains(&needle), "{args:?}: `{needle}` not in {err}");
        assert!(err.starts_with("glint: "), "{err}");
        // A usage error is explained as clap explains it; any other is one line.
        if code != 2 {
            assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        }
        assert!(!err.contains("panicked"), "{err}");
    }
    assert!(!diff.exists(), "no diff map for images that cannot be compared");
}
