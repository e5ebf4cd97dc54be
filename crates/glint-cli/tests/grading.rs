//! `glint test --submissions` end to end on the GPU (a software adapter in CI; no
//! adapter is a failure, never a skip): a folder of four students' images
//! (right, slightly wrong, wrong size and missing, unreadable), made here by
//! rendering with Glint and then changing the PNGs, is graded in one run
//! against a reference Glint renders and one given as a file. That run writes
//! Gradescope results.json, JUnit, a report per student and a class summary.
//! A class folder as it arrives (misnamed files, `__MACOSX`, names that
//! collide, students who left) is graded with a reference file, no GPU.

mod suite;

use std::path::Path;

use suite::{arg, chromium, glint, stderr, stdout, SPHERE};

const MANIFEST: &str = r#"
name = "course"

[[case]]
name = "sphere"
image = "sphere.png"
scene = "scenes/sphere.toml"
points = 10
render = { max_depth = 2 }

[[case.partial]]
flip = 0.2
points = 4

[[case]]
name = "ball"
image = "{student}-ball.png"
golden = "refs/ball.png"
points = 5
"#;

fn render(scene: &Path, out: &Path, extra: &[&str]) {
    let mut args = vec!["render", arg(scene), "-o", arg(out), "-q"];
    args.extend(extra);
    let o = glint(&args);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// The course folder: the manifest, its scene and its reference file, and
/// the submissions of ann (right), bob (a white block on the sphere), cat
/// (half size, and no ball) and dan (a sphere.png that is not a PNG).
fn course() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path();
    for folder in ["scenes", "refs", "subs/ann", "subs/bob", "subs/cat", "subs/dan", "subs/.git"] {
        std::fs::create_dir_all(root.join(folder)).unwrap();
    }
    let scene = root.join("scenes/sphere.toml");
    std::fs::write(&scene, SPHERE).unwrap();
    std::fs::write(root.join("course.toml"), MANIFEST).unwrap();
    render(&scene, &root.join("refs/ball.png"), &["--view", "normals"]);

    let right = root.join("right.png");
    render(&scene, &right, &["--max-depth", "2"]);
    let right_image = image::open(&right).unwrap().to_rgb8();
    right_image.save(root.join("subs/ann/sphere.png")).unwrap();
    let mut slightly_wrong = right_image.clone();
    for y in 10..13 {
        for x in 20..24 {
            slightly_wrong.put_pixel(x, y, image::Rgb([255, 255, 255]));
        }
    }
    slightly_wrong.save(root.join("subs/bob/sphere.png")).unwrap();
    image::imageops::resize(&right_image, 24, 18, image::imageops::FilterType::Triangle).save(root.join("subs/cat/sphere.png")).unwrap();
    std::fs::write(root.join("subs/dan/sphere.png"), b"GIF89a, not a PNG").unwrap();
    for student in ["ann", "bob", "dan"] {
        std::fs::copy(root.join("refs/ball.png"), root.join(format!("subs/{student}/{student}-ball.png"))).unwrap();
    }
    dir
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))).unwrap()
}

#[test]
fn a_class_is_graded_in_one_run_with_every_report() {
    let dir = course();
    let root = dir.path();
    let report = root.join("report");
    let junit = root.join("junit.xml");
    let o = glint(&[
        "test",
        arg(&root.join("course.toml")),
        "--submissions",
        arg(&root.join("subs")),
        "--report",
        arg(&report),
        "--junit",
        arg(&junit),
    ]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}{}", stderr(&o));
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 4 * 3 + 1, "{out}");
    assert!(lines[0].starts_with("ok      ann/sphere: flip 0 <= 0.01") && lines[0].ends_with("(10/10 points)"), "{out}");
    assert_eq!(lines[2], "ann: 2 passed, 0 failed; 15/15 points");
    assert!(lines[3].starts_with("FAIL    bob/sphere: flip ") && lines[3].contains(", worst region 4x4 at ("), "{out}");
    assert!(lines[3].ends_with("; partial credit: flip <= 0.2 (4/10 points)"), "{out}");
    assert_eq!(lines[5], "bob: 1 passed, 1 failed; 9/15 points");
    assert_eq!(lines[6], "FAIL    cat/sphere: wrong size: the submission is 24x18, the reference 48x36 (0/10 points)");
    let missing = root.join("subs/cat/cat-ball.png");
    assert_eq!(lines[7], format!("FAIL    cat/ball: no image: {} is missing (0/5 points)", missing.display()));
    let unreadable = root.join("subs/dan/sphere.png");
    assert!(lines[9].starts_with(&format!("FAIL    dan/sphere: {}: not a readable image", unreadable.display())), "{out}");
    assert_eq!(lines[11], "dan: 1 passed, 1 failed; 5/15 points");
    assert_eq!(lines[12], format!("wrote {}", report.join("index.html").display()));

    // Gradescope: scores, statuses, and outputs that name the case's settings
    // and where the difference is.
    let scores: Vec<f64> = ["ann", "bob", "cat", "dan"].iter().map(|s| json(&report.join(s).join("results.json"))["score"].as_f64().unwrap()).collect();
    assert_eq!(scores, [15.0, 9.0, 0.0, 5.0]);
    let bob = json(&report.join("bob/results.json"));
    assert_eq!(bob["output"], "course: 1 passed, 1 failed; 9/15 points");
    let sphere = &bob["tests"][0];
    assert_eq!((&sphere["name"], &sphere["score"], &sphere["max_score"], &sphere["status"]), (&"sphere".into(), &4.0.into(), &10.0.into(), &"failed".into()));
    let output = sphere["output"].as_str().unwrap();
    assert!(output.contains(", worst region 4x4 at ("), "{output}");
    assert!(output.contains("\n- settings: view shaded, max depth 2, 1 spp, 48x36\n"), "{output}");
    assert!(output.contains(&format!("\n- submission: {}", root.join("subs/bob/sphere.png").display())), "{output}");
    // A failure is Markdown with the images side by side; a pass plain text.
    assert_eq!((&sphere["output_format"], bob["tests"][1].get("output_format")), (&"md".into(), None));
    for role in ["reference", "submission", "diff"] {
        assert!(output.contains(&format!("![{role}](data:image/png;base64,")), "{role}: {output}");
    }
    assert_eq!(bob["tests"][1]["status"], "passed");
    assert_eq!(bob["tests"][1]["output"].as_str().unwrap().lines().nth(1), Some("settings: reference image, 48x36"));
    let cat = json(&report.join("cat/results.json"));
    assert!(cat["tests"][0]["output"].as_str().unwrap().starts_with("wrong size: the submission is 24x18, the reference 48x36\n"));
    assert_eq!((&cat["tests"][1]["status"], &cat["tests"][1]["score"]), (&"failed".into(), &0.0.into()));

    // The region named is where bob's block is.
    let at = output.split("worst region 4x4 at (").nth(1).unwrap();
    let (x, y) = at.split_once(')').unwrap().0.split_once(", ").unwrap();
    let (x, y): (u32, u32) = (x.parse().unwrap(), y.parse().unwrap());
    assert!((17..=23).contains(&x) && (7..=12).contains(&y), "({x}, {y})");

    // JUnit: a testsuite per student.
    let xml = std::fs::read_to_string(&junit).unwrap();
    assert!(xml.contains("<testsuites name=\"course\" tests=\"8\" failures=\"4\" errors=\"0\">"), "{xml}");
    for (student, failures) in [("ann", 0), ("bob", 1), ("cat", 2), ("dan", 1)] {
        assert!(xml.contains(&format!("<testsuite name=\"{student}\" tests=\"2\" failures=\"{failures}\"")), "{student}: {xml}");
    }
    assert!(xml.contains("<failure type=\"no-image\""), "{xml}");

    // Bob's report: his case's settings, and his image beside the reference
    // at the worst region, magnified from the files written beside it.
    let page = std::fs::read_to_string(report.join("bob/index.html")).unwrap();
    assert!(page.contains("<td>view shaded, max depth 2, 1 spp, 48x36</td>"), "{page}");
    for role in ["reference", "submission"] {
        assert!(page.contains(&format!("<img src=\"sphere-{role}-zoom.png\" alt=\"{role}, worst region magnified\"")), "{page}");
        let zoom = image::open(report.join(format!("bob/sphere-{role}-zoom.png"))).unwrap().to_rgb8();
        assert_eq!(zoom.dimensions(), (192, 192), "{role}");
    }
    let zoom = image::open(report.join("bob/sphere-submission-zoom.png")).unwrap().to_rgb8();
    assert!(zoom.pixels().any(|p| p.0 == [255, 255, 255]), "the white block is in the magnified region");
    assert!(report.join("bob/sphere-diff.png").is_file());

    // The class summary: a row per student with their points, sortable.
    let class = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert_eq!(class.matches("<tr><td data-sort=").count(), 4, "{class}");
    assert!(class.contains("<td data-sort=\"bob\"><a href=\"bob/index.html\">bob</a></td><td data-sort=\"9\">9/15</td><td class=\"failed\" data-sort=\"4\""), "{class}");
    assert!(class.contains("<th data-type=\"number\">sphere</th><th data-type=\"number\">ball</th>"), "{class}");
    // Clicking the score's header in Chromium puts the best first; again, last.
    let click = "document.querySelectorAll('#class th')[1].click();";
    for (clicks, order) in [(1, ["ann", "bob", "dan", "cat"]), (2, ["cat", "dan", "bob", "ann"])] {
        let page = report.join(format!("sorted-{clicks}.html"));
        std::fs::write(&page, class.replace("</body>", &format!("<script>{}</script></body>", click.repeat(clicks)))).unwrap();
        let o = chromium(&["--dump-dom", &format!("file://{}", page.display())]);
        assert!(o.status.success(), "{}", stderr(&o));
        let rows: Vec<String> = stdout(&o).split("<tr><td data-sort=\"").skip(1).map(|r| r.split('"').next().unwrap().to_string()).collect();
        assert_eq!(rows, order, "{clicks} click(s)");
    }

    // Gradescope's per-submission run writes the same results for one student.
    let results = root.join("results.json");
    let o = glint(&["test", arg(&root.join("course.toml")), "--submission", arg(&root.join("subs/bob")), "--gradescope", arg(&results)]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(std::fs::read(&results).unwrap(), std::fs::read(report.join("bob/results.json")).unwrap());
}

#[test]
fn grading_errors_are_one_line() {
    let dir = course();
    let root = dir.path();
    let manifest = root.join("course.toml");
    let empty = tempfile::tempdir().unwrap();
    for (args, code, needle) in [
        (vec![arg(&manifest)], 2, "its cases grade submitted images: give --submissions DIR".to_string()),
        (vec![arg(&manifest), "--submissions", arg(empty.path())], 3, "no student folders in the submissions directory".into()),
        (vec![arg(&manifest), "--submissions", arg(&root.join("subs")), "--case", "nope"], 2, "no case named `nope`".into()),
    ] {
        let mut all = vec!["test"];
        all.extend(&args);
        let o = glint(&all);
        let stderr = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {stderr}");
        assert!(stderr.contains(&needle) && stderr.trim_end().lines().count() == 1, "{args:?}: {stderr}");
    }
    // A reference that cannot be made is named, after every student's grades are written.
    std::fs::write(root.join("scenes/sphere.toml"), "[image]\nwidth = \"wide\"\n").unwrap();
    let o = glint(&["test", arg(&manifest), "--submissions", arg(&root.join("subs"))]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(stderr(&o).starts_with(&format!("glint: case `sphere`: reference: {}:2:", root.join("scenes/sphere.toml").display())), "{}", stderr(&o));
}

#[test]
fn a_class_folder_is_graded_as_it_arrives() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path();
    let subs = root.join("subs");
    let image = image::RgbImage::from_fn(16, 12, |x, y| image::Rgb([(x * 15) as u8, (y * 20) as u8, 120]));
    let files = ["ann/Ball.png", "bob lee/ball.png", "bob_lee/ball.png", "cy/hw2/ball.png", "dee/ball.ppm", "__MACOSX/ann/._Ball.png", ".git/ball.png"];
    for file in files {
        let path = subs.join(file);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        image.save_with_format(&path, image::ImageFormat::Png).unwrap();
    }
    image.save(root.join("ref.png")).unwrap();
    std::fs::write(root.join("course.toml"), "[[case]]\nname = \"ball\"\nimage = \"ball.png\"\ngolden = \"ref.png\"\npoints = 2\n").unwrap();
    // A report from before: a student who has left, and a folder of the teacher's.
    let report = root.join("report");
    for folder in ["zed", "notes"] {
        std::fs::create_dir_all(report.join(folder)).unwrap();
    }
    std::fs::write(report.join("zed/results.json"), "{}").unwrap();
    std::fs::write(report.join("notes/todo.txt"), "").unwrap();

    let o = glint(&["test", arg(&root.join("course.toml")), "--submissions", arg(&subs), "--report", arg(&report)]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}{}", stderr(&o));
    let missing = |student: &str| format!("FAIL    {student}/ball: no image: {} is missing; did you mean", subs.join(student).join("ball.png").display());
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], format!("{} Ball.png (the letter case differs)? (0/2 points)", missing("ann")), "{out}");
    assert!(lines[2].starts_with("ok      bob lee/ball: flip 0 <= 0.01") && lines[4].starts_with("ok      bob_lee/ball: flip 0"), "{out}");
    assert_eq!(lines[6], format!("{} hw2/ball.png (inside the folder hw2/)? (0/2 points)", missing("cy")), "{out}");
    assert_eq!(lines[8], format!("{} ball.ppm (a .ppm file, not .png)? (0/2 points)", missing("dee")), "{out}");
    assert_eq!(lines[10], format!("removed {}: no longer in the class", report.join("zed").display()), "{out}");
    assert_eq!(lines[11], format!("wrote {}", report.join("index.html").display()), "{out}");
    assert_eq!(lines.len(), 12, "archivers' and hidden folders are no students: {out}");

    // Two students whose names make one folder name each have their own.
    let class = std::fs::read_to_string(report.join("index.html")).unwrap();
    for (student, folder) in [("bob lee", "bob_lee-2"), ("bob_lee", "bob_lee")] {
        assert_eq!(json(&report.join(folder).join("results.json"))["score"], 2.0, "{student}");
        assert!(class.contains(&format!("<a href=\"{folder}/index.html\">{student}</a>")), "{class}");
    }
    assert!(!report.join("zed").exists() && report.join("notes/todo.txt").is_file());
    assert!(!report.join("__MACOSX").exists() && !report.join(".git").exists());
}

/// A course whose students hand in PPM, as many ray-tracing courses ask: the
/// manifest names `.ppm` images, against a scene and against a PPM reference,
/// and each student's raw or plain file is graded with no conversion.
#[test]
fn a_class_of_ppm_images_is_graded() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path();
    for folder in ["refs", "subs/ann", "subs/bob", "subs/cat", "subs/dan"] {
        std::fs::create_dir_all(root.join(folder)).unwrap();
    }
    let scene = root.join("sphere.toml");
    std::fs::write(&scene, SPHERE).unwrap();
    std::fs::write(
        root.join("course.toml"),
        "name = \"ppm\"\n\n[[case]]\nname = \"balls\"\nimage = \"balls_s1.ppm\"\nscene = \"sphere.toml\"\npoints = 10\n\n\
         [[case.partial]]\nflip = 0.2\npoints = 4\n\n\
         [[case]]\nname = \"normals\"\nimage = \"normals.ppm\"\ngolden = \"refs/normals.ppm\"\npoints = 5\n",
    )
    .unwrap();
    render(&scene, &root.join("refs/normals.ppm"), &["--view", "normals", "--plain"]);
    // ann: Glint's own raw PPMs; bob: plain ones with a comment, as a student's
    // program writes them, and one pixel block wrong; cat: a file cut short;
    // dan: a PGM, not a PPM.
    render(&scene, &root.join("subs/ann/balls_s1.ppm"), &[]);
    std::fs::copy(root.join("refs/normals.ppm"), root.join("subs/ann/normals.ppm")).unwrap();
    let right = glint_gpu::read_ppm(&std::fs::read(root.join("subs/ann/balls_s1.ppm")).unwrap()).unwrap();
    let mut samples = right.samples.clone();
    for y in 10..13 {
        for x in 20..24 {
            let at = (y * right.width as usize + x) * 3;
            samples[at..at + 3].copy_from_slice(&[255; 3]);
        }
    }
    let text: Vec<String> = samples.iter().map(u16::to_string).collect();
    let plain = format!("P3\n# balls, by bob\n{} {}\n255\n{}\n", right.width, right.height, text.join("\n"));
    std::fs::write(root.join("subs/bob/balls_s1.ppm"), plain).unwrap();
    std::fs::copy(root.join("refs/normals.ppm"), root.join("subs/bob/normals.ppm")).unwrap();
    let raw = std::fs::read(root.join("subs/ann/balls_s1.ppm")).unwrap();
    std::fs::write(root.join("subs/cat/balls_s1.ppm"), &raw[..raw.len() / 2]).unwrap();
    std::fs::write(root.join("subs/dan/balls_s1.ppm"), b"P5\n1 1\n255\n\x00").unwrap();

    let report = root.join("report");
    let o = glint(&["test", arg(&root.join("course.toml")), "--submissions", arg(&root.join("subs")), "--report", arg(&report)]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}{}", stderr(&o));
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines[0].starts_with("ok      ann/balls: flip 0 <= 0.01") && lines[0].ends_with("(10/10 points)"), "{out}");
    assert!(lines[1].starts_with("ok      ann/normals: flip 0 <= 0.01"), "{out}");
    assert!(lines[3].starts_with("FAIL    bob/balls: flip ") && lines[3].ends_with("(4/10 points)"), "{out}");
    let cut = root.join("subs/cat/balls_s1.ppm");
    let promised = format!("the header promises {}x{} pixels ({} bytes of samples), but", right.width, right.height, right.samples.len());
    assert!(lines[6].starts_with(&format!("FAIL    cat/balls: {}: truncated: {promised}", cut.display())), "{out}");
    let pgm = root.join("subs/dan/balls_s1.ppm");
    assert!(lines[9].starts_with(&format!("FAIL    dan/balls: {}: not a PPM: it starts with P5, a PGM (greymap)", pgm.display())), "{out}");
    let scores: Vec<f64> = ["ann", "bob", "cat", "dan"].iter().map(|s| json(&report.join(s).join("results.json"))["score"].as_f64().unwrap()).collect();
    assert_eq!(scores, [15.0, 9.0, 0.0, 0.0]);
}
