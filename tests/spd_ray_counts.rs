//! SPD's testing procedure (its Readme, "Testing Procedures"): 512×512, the
//! eye ray at depth 1, trees to depth 5 with no adaptive cutoff, a reflection
//! ray at every reflecting or transmitting hit and a refraction ray at every
//! transmitting one. Its table gives the ray counts a classic tracer makes on
//! the seven benchmark databases "within about 10%"; Glint must be within 10 %.

mod support;

use std::path::Path;

/// SPD's table: eye rays that hit, reflect, refract and shadow rays, for
/// 513 × 513 eye rays through pixel corners.
const TABLE: [(&str, [u64; 4]); 7] = [
    ("balls", [263_169, 175_095, 0, 954_368]),
    ("gears", [245_086, 304_643, 207_564, 2_246_955]),
    ("mount", [173_125, 354_769, 354_769, 412_922]),
    ("rings", [263_169, 315_236, 0, 1_085_002]),
    ("teapot", [161_120, 225_248, 0, 407_656]),
    ("tetra", [49_788, 0, 0, 46_112]),
    ("tree", [169_836, 0, 0, 1_097_419]),
];

#[test]
fn classic_databases_give_the_ray_counts_of_spds_table() {
    // Glint traces one ray through each of the 512² pixel centres.
    let scale = (512.0 * 512.0) / (513.0 * 513.0);
    let mut report = Vec::new();
    let mut failed = false;
    for (name, table) in TABLE {
        let mut scene = glint_scene::load(Path::new(&format!("spd:{name}"))).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((scene.width, scene.height), (512, 512), "{name}");
        scene.render.max_depth = 5;
        scene.render.cutoff = 0.0;
        let (_, stats) = support::render(&scene);
        let got = [stats.eye_hit, stats.reflect, stats.refract, stats.shadow];
        for ((kind, want), got) in ["eye hit", "reflect", "refract", "shadow"].iter().zip(table).zip(got) {
            let want = want as f64 * scale;
            let off = if want == 0.0 { if got == 0 { 0.0 } else { f64::INFINITY } } else { got as f64 / want - 1.0 };
            let ok = off.abs() <= 0.10;
            failed |= !ok;
            report.push(format!("{name:>6} {kind:>7}: {got:>9} vs {want:>11.0} ({:+.1} %){}", off * 100.0, if ok { "" } else { "  <- over 10 %" }));
        }
    }
    let report = report.join("\n");
    eprintln!("{report}");
    assert!(!failed, "ray counts differ from SPD's table by more than 10 %:\n{report}");
}
