//! `glint spd` and `spd:NAME[:SIZE]` scene arguments, end to end.

use std::process::{Command, Output};

fn glint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint")).args(args).output().expect("glint runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn spd_writes_a_database_as_nff() {
    let o = glint(&["spd", "tetra", "--size", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let nff = String::from_utf8(o.stdout).unwrap();
    assert!(nff.starts_with("b ") && nff.contains("\nv\nfrom "), "{nff}");
    assert_eq!(nff.lines().filter(|l| l.starts_with("p ")).count(), 16, "tetra size 2: 4² polygons");

    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("balls.nff");
    let o = glint(&["spd", "balls", "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let balls = std::fs::read_to_string(&out).unwrap();
    assert_eq!(balls.lines().filter(|l| l.starts_with("s ")).count(), 7381, "balls at its benchmark size, 4");
}

#[test]
fn spd_scenes_render_without_any_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("tetra.png");
    let o = glint(&["render", "spd:tetra:3", "-o", out.to_str().unwrap(), "--width", "64", "--height", "64", "--stats", "--json", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stats: serde_json::Value = serde_json::from_str(&String::from_utf8(o.stdout).unwrap()).unwrap();
    assert!(stats["eye_hit"].as_u64().unwrap() > 0);
    assert_eq!(image::open(&out).unwrap().to_rgb8().dimensions(), (64, 64));
}

#[test]
fn a_bad_spd_name_or_size_is_one_line_and_a_usage_error() {
    for (args, needle) in [
        (vec!["render", "spd:teapots", "-o", "x.png"], "no SPD database named `teapots`"),
        (vec!["render", "spd:teapot:0", "-o", "x.png"], "SPD teapot has no size `0`"),
        (vec!["bench", "spd:balls:big"], "SPD balls has no size `big`"),
        (vec!["view", "spd:mount:8"], "SPD mount has no size `8`: a whole number from 1 to 7"),
        (vec!["spd", "tree", "--size", "0"], "SPD tree has no size `0`"),
        (vec!["spd", "gear"], "no SPD database named `gear`"),
    ] {
        let o = glint(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let message = stderr(&o);
        assert!(message.contains(needle), "{args:?}: {message}");
        assert!(!message.contains("panicked"), "{args:?}: {message}");
    }
}
