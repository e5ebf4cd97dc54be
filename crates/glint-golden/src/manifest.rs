//! Test suites: the cases of a manifest file, or of a directory of scenes
//! each with its golden image beside it. docs/golden-ci.md describes the
//! manifest's format.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glint_scene::{LoadError, Location};
use serde::Deserialize;
use toml::Spanned;

use crate::criteria::Criteria;
use crate::image_io;
use crate::scoring::{BandDef, Scoring};
use crate::settings::{Checked, CompareSettings, PositiveFinite, RenderSettings, Visibility};

/// One scene, rendered and compared with one golden image.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    pub name: String,
    /// A scene file, or `spd:NAME[:SIZE]`.
    pub scene: PathBuf,
    pub golden: PathBuf,
    pub render: RenderSettings,
    pub criteria: Criteria,
}

impl Case {
    pub fn file_stem(&self) -> String {
        file_stem_of(&self.name)
    }
}

/// `name` with anything but letters, digits, `.`, `_` and `-` replaced by
/// `_`: the stem of a case's files, or a student's folder, in a report.
pub fn file_stem_of(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') { c } else { '_' }).collect()
}

/// A `[[case]]` with an `image`: what each student submits for it and what
/// that is compared with.
#[derive(Debug, Clone, PartialEq)]
pub struct GradedCase {
    pub name: String,
    /// The submitted image's path inside each student's folder.
    pub image: String,
    pub reference: Reference,
    pub render: RenderSettings,
    pub criteria: Criteria,
    pub scoring: Scoring,
    /// When Gradescope shows the case's test to the student; `None` leaves it
    /// to Gradescope (visible).
    pub visibility: Option<Visibility>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Reference {
    /// A scene (or `spd:NAME[:SIZE]`) that Glint renders with the case's settings.
    Scene(PathBuf),
    /// An image file.
    File(PathBuf),
}

impl GradedCase {
    pub fn file_stem(&self) -> String {
        file_stem_of(&self.name)
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Suite {
    /// Names the suite in reports and JUnit XML.
    pub name: String,
    /// The manifest or directory the suite was read from.
    pub source: PathBuf,
    pub cases: Vec<Case>,
    /// The cases that grade submitted images.
    pub graded: Vec<GradedCase>,
}

const SCENE_EXTENSIONS: [&str; 4] = ["toml", "nff", "ray", "obj"];

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ManifestFile {
    name: Option<String>,
    #[serde(default)]
    render: RenderSettings,
    #[serde(default)]
    compare: CompareSettings,
    #[serde(default)]
    case: Vec<Spanned<CaseDef>>,
    #[serde(default)]
    scenes: Vec<Spanned<ScenesDef>>,
}

/// `[[case]]`: one scene and its golden; or, with `image`, a submitted
/// image and its reference, a scene or a file.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CaseDef {
    name: Option<String>,
    scene: Option<String>,
    golden: Option<PathBuf>,
    image: Option<String>,
    points: Option<Checked<PositiveFinite>>,
    #[serde(default)]
    partial: Vec<Spanned<BandDef>>,
    visibility: Option<Visibility>,
    #[serde(default)]
    render: RenderSettings,
    #[serde(default)]
    compare: CompareSettings,
}

/// `[[scenes]]`: every scene file in a directory.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ScenesDef {
    dir: PathBuf,
    #[serde(default)]
    recursive: bool,
    /// Files or directories, relative to `dir`, left out.
    #[serde(default)]
    exclude: Vec<PathBuf>,
    /// Where the goldens are, named after each scene's path below `dir`
    /// (`gallery/mirror.toml` → `gallery-mirror.png`); default: beside each scene.
    goldens: Option<PathBuf>,
    #[serde(default)]
    render: RenderSettings,
    #[serde(default)]
    compare: CompareSettings,
}

impl Suite {
    /// A manifest file, or a directory (see [`Suite::from_directory`]).
    pub fn load(path: &Path) -> Result<Suite, LoadError> {
        if path.is_dir() { Suite::from_directory(path) } else { Suite::from_manifest(path) }
    }

    /// Every scene file directly in `dir`, each compared with the PNG of the
    /// same name beside it, with the default options. Scenes' meshes belong
    /// in a subdirectory, which is not searched.
    pub fn from_directory(dir: &Path) -> Result<Suite, LoadError> {
        let scenes = scene_files(dir, false, &[]).map_err(|e| LoadError::new(dir, None, format!("cannot read directory: {e}")))?;
        if scenes.is_empty() {
            return Err(LoadError::new(dir, None, "no scene files (.toml, .nff, .ray or .obj) in the directory"));
        }
        let criteria = CompareSettings::default().criteria();
        let cases = scenes
            .into_iter()
            .map(|(name, scene)| {
                let golden = scene.with_extension("png");
                Case { name, scene, golden, render: RenderSettings::default(), criteria }
            })
            .collect();
        let suite = Suite { name: directory_name(dir), source: dir.to_path_buf(), cases, graded: Vec::new() };
        suite.check_names(|_| None)?;
        Ok(suite)
    }

    pub fn from_manifest(path: &Path) -> Result<Suite, LoadError> {
        let source = std::fs::read_to_string(path).map_err(|e| LoadError::new(path, None, format!("cannot read manifest: {e}")))?;
        let file: ManifestFile = toml::from_str(&source).map_err(|e| {
            let location = e.span().map(|s| Location::of_offset(&source, s.start));
            LoadError::new(path, location, e.message().trim().replace('\n', " "))
        })?;
        let at = |offset: usize, message: String| LoadError::new(path, Some(Location::of_offset(&source, offset)), message);
        let base = path.parent().unwrap_or(Path::new(""));

        // Cases keep the order of their tables in the file.
        let mut entries: Vec<(usize, Vec<Case>)> = Vec::new();
        let mut graded = Vec::new();
        for def in &file.case {
            let start = def.span().start;
            match case_of(def.get_ref(), base, &file.render, &file.compare).map_err(|(offset, m)| at(offset.unwrap_or(start), m))? {
                Parsed::Golden(case) => entries.push((start, vec![case])),
                Parsed::Graded(case) => graded.push((start, case)),
            }
        }
        for def in &file.scenes {
            let cases = scene_cases(def.get_ref(), base, &file.render, &file.compare).map_err(|m| at(def.span().start, m))?;
            entries.push((def.span().start, cases));
        }
        entries.sort_by_key(|(offset, _)| *offset);
        let starts: Vec<(usize, usize)> = entries.iter().map(|(offset, cases)| (*offset, cases.len())).collect();
        let cases: Vec<Case> = entries.into_iter().flat_map(|(_, cases)| cases).collect();
        if cases.is_empty() && graded.is_empty() {
            return Err(LoadError::new(path, None, "no cases: add [[case]] or [[scenes]] tables"));
        }
        let mut stems = HashMap::new();
        for (offset, case) in &graded {
            if let Some(earlier) = stems.insert(case.file_stem(), &case.name) {
                return Err(at(*offset, format!("graded cases `{earlier}` and `{}` have the same name", case.name)));
            }
        }
        let graded = graded.into_iter().map(|(_, case)| case).collect();
        let name = file.name.unwrap_or_else(|| path.file_stem().map_or_else(|| "glint".into(), |s| s.to_string_lossy().into_owned()));
        let suite = Suite { name, source: path.to_path_buf(), cases, graded };
        // A duplicate is reported at the table that brought it in.
        let table_of = |index: usize| {
            let mut end = 0;
            let (offset, _) = starts.iter().find(|(_, count)| {
                end += count;
                index < end
            })?;
            Some(Location::of_offset(&source, *offset))
        };
        suite.check_names(table_of)?;
        Ok(suite)
    }

    /// Two cases with one name, or one report file name, would overwrite
    /// each other's golden or report images.
    fn check_names(&self, location_of: impl Fn(usize) -> Option<Location>) -> Result<(), LoadError> {
        let mut seen: HashMap<String, &Case> = HashMap::new();
        for (index, case) in self.cases.iter().enumerate() {
            if let Some(earlier) = seen.insert(case.file_stem(), case) {
                return Err(LoadError::new(
                    &self.source,
                    location_of(index),
                    format!(
                        "cases `{}` ({}) and `{}` ({}) have the same name",
                        earlier.name,
                        earlier.scene.display(),
                        case.name,
                        case.scene.display()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The cases named, in the suite's order; all of them when `names` is empty.
    pub fn select(&self, names: &[String]) -> Result<Vec<&Case>, String> {
        chosen(&self.source, &self.cases, |c| &c.name, names)
    }

    /// The graded cases named, as [`Suite::select`] chooses.
    pub fn select_graded(&self, names: &[String]) -> Result<Vec<&GradedCase>, String> {
        chosen(&self.source, &self.graded, |c| &c.name, names)
    }
}

fn chosen<'a, T>(source: &Path, all: &'a [T], name: fn(&T) -> &String, names: &[String]) -> Result<Vec<&'a T>, String> {
    if let Some(unknown) = names.iter().find(|n| !all.iter().any(|c| name(c) == *n)) {
        return Err(format!("{}: no case named `{unknown}`", source.display()));
    }
    Ok(all.iter().filter(|c| names.is_empty() || names.contains(name(c))).collect())
}

fn directory_name(dir: &Path) -> String {
    let absolute = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
    absolute.components().next_back().map_or_else(|| "scenes".into(), |c| c.as_os_str().to_string_lossy().into_owned())
}

enum Parsed {
    Golden(Case),
    Graded(GradedCase),
}

/// A case, or the error and the offset of the band it is about (else the case's).
fn case_of(def: &CaseDef, base: &Path, render: &RenderSettings, compare: &CompareSettings) -> Result<Parsed, (Option<usize>, String)> {
    const NO_SCENE: &str = "scene: a case needs a `scene` (or an `image` to grade)";
    let fail = |message: &str| Err((None, message.to_string()));
    if def.scene.is_none() && def.image.is_none() {
        return fail(NO_SCENE);
    }
    let spd = def.scene.as_deref().and_then(|s| glint_scene::spd::spec_of(Path::new(s)));
    let stem = |path: &str| Path::new(path).file_stem().map(|s| s.to_string_lossy().into_owned());
    let name = match (&def.name, spd) {
        (Some(name), _) => name.clone(),
        (None, Some(spec)) => format!("spd-{}", spec.replace(':', "-")),
        (None, None) => def.scene.as_deref().or(def.image.as_deref()).and_then(stem).unwrap_or_default(),
    };
    if name.is_empty() {
        return fail("name: a case needs a name");
    }
    let scene = def.scene.as_ref().map(|scene| if spd.is_some() { PathBuf::from(scene) } else { base.join(scene) });
    let render = render.overridden_by(&def.render);
    let criteria = compare.overridden_by(&def.compare).criteria();
    let Some(image) = &def.image else {
        if def.points.is_some() || !def.partial.is_empty() {
            return fail("points: only a case with an `image` to grade earns points");
        }
        if def.visibility.is_some() {
            return fail("visibility: only a case with an `image` to grade is a Gradescope test");
        }
        let Some(scene) = scene else { return fail(NO_SCENE) };
        let golden = base.join(def.golden.clone().unwrap_or_else(|| PathBuf::from(format!("{name}.png"))));
        check_golden(&golden).map_err(|m| (None, m))?;
        return Ok(Parsed::Golden(Case { name, scene, golden, render, criteria }));
    };
    check_golden(Path::new(image)).map_err(|m| (None, m.replacen("golden:", "image:", 1)))?;
    let reference = match (scene, &def.golden) {
        (Some(scene), None) => Reference::Scene(scene),
        (None, Some(golden)) => {
            let golden = base.join(golden);
            check_golden(&golden).map_err(|m| (None, m))?;
            Reference::File(golden)
        }
        (Some(_), Some(_)) => return fail("golden: a graded `image` is compared with a `scene` Glint renders or a `golden` file, not both"),
        (None, None) => return fail("image: a graded `image` needs its reference: a `scene` for Glint to render, or a `golden` file"),
    };
    let scoring = Scoring::of(def.points.map(|p| p.value), &def.partial, &criteria)?;
    Ok(Parsed::Graded(GradedCase { name, image: image.clone(), reference, render, criteria, scoring, visibility: def.visibility }))
}

fn scene_cases(def: &ScenesDef, base: &Path, render: &RenderSettings, compare: &CompareSettings) -> Result<Vec<Case>, String> {
    let dir = base.join(&def.dir);
    let scenes = scene_files(&dir, def.recursive, &def.exclude).map_err(|e| format!("dir: cannot read {}: {e}", dir.display()))?;
    if scenes.is_empty() {
        return Err(format!("dir: no scene files (.toml, .nff, .ray or .obj) in {}", dir.display()));
    }
    let render = render.overridden_by(&def.render);
    let criteria = compare.overridden_by(&def.compare).criteria();
    scenes
        .into_iter()
        .map(|(name, scene)| {
            let golden = match &def.goldens {
                Some(goldens) => base.join(goldens).join(format!("{name}.png")),
                None => scene.with_extension("png"),
            };
            check_golden(&golden)?;
            Ok(Case { name, scene, golden, render: render.clone(), criteria })
        })
        .collect()
}

fn check_golden(golden: &Path) -> Result<(), String> {
    match image_io::format_of(golden) {
        Some(_) => Ok(()),
        None => Err(format!("golden: {}: use a {} file", golden.display(), glint_gpu::Format::EXTENSIONS)),
    }
}

/// The scene files under `root`, sorted, each with its name: its path below
/// `root` without the extension, `/` written `-`.
fn scene_files(root: &Path, recursive: bool, exclude: &[PathBuf]) -> std::io::Result<Vec<(String, PathBuf)>> {
    let mut found = Vec::new();
    collect(root, root, recursive, exclude, &mut found)?;
    Ok(found
        .into_iter()
        .map(|path| {
            let relative = path.strip_prefix(root).unwrap_or(&path).with_extension("");
            let name = relative.components().map(|c| c.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("-");
            (name, path)
        })
        .collect())
}

fn collect(root: &Path, dir: &Path, recursive: bool, exclude: &[PathBuf], found: &mut Vec<PathBuf>) -> std::io::Result<()> {
    let mut entries = std::fs::read_dir(dir)?.map(|e| e.map(|e| e.path())).collect::<Result<Vec<_>, _>>()?;
    entries.sort();
    for path in entries {
        // Hidden files are editors' and tools' own (swap files, temporaries).
        let hidden = path.file_name().is_some_and(|n| n.to_string_lossy().starts_with('.'));
        if hidden || exclude.iter().any(|x| path.strip_prefix(root).is_ok_and(|rel| rel == x)) {
            continue;
        }
        if path.is_dir() {
            if recursive {
                collect(root, &path, recursive, exclude, found)?;
            }
        } else if path.extension().is_some_and(|e| SCENE_EXTENSIONS.contains(&e.to_string_lossy().to_ascii_lowercase().as_str())) {
            found.push(path);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::Metric;
    use crate::settings::Bounded;

    fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, text).unwrap();
        path
    }

    #[test]
    fn a_manifest_lists_cases_with_defaults_and_overrides() {
        let dir = tempfile::tempdir().unwrap();
        let manifest = write(
            dir.path(),
            "suite.toml",
            r#"
name = "course"
[render]
spp = 4
[compare]
threshold = 0.02

[[case]]
scene = "scenes/a.toml"

[[scenes]]
dir = "more"
goldens = "goldens"
compare = { metric = "rmse" }

[[case]]
name = "balls"
scene = "spd:balls:1"
golden = "refs/balls.exr"
render = { spp = 1, width = 64, height = 48 }
"#,
        );
        write(dir.path(), "more/b.nff", "");
        write(dir.path(), "more/c.obj", "");
        let suite = Suite::from_manifest(&manifest).unwrap();
        assert_eq!(suite.name, "course");
        let names: Vec<&str> = suite.cases.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["a", "b", "c", "balls"]);
        let [a, b, _, balls] = &suite.cases[..] else { unreachable!() };
        assert_eq!(a.scene, dir.path().join("scenes/a.toml"));
        assert_eq!(a.golden, dir.path().join("a.png"));
        assert_eq!(a.render.spp, Some(Bounded(4)));
        assert_eq!((a.criteria.metric, a.criteria.threshold), (Metric::Flip, 0.02));
        assert_eq!(b.golden, dir.path().join("goldens/b.png"));
        assert_eq!(b.criteria, Criteria::for_metric(Metric::Rmse));
        assert_eq!(balls.scene, PathBuf::from("spd:balls:1"));
        assert_eq!(balls.golden, dir.path().join("refs/balls.exr"));
        assert_eq!((balls.render.spp, balls.render.width), (Some(Bounded(1)), Some(Bounded(64))));
    }

    #[test]
    fn scenes_tables_recurse_exclude_and_name_by_path() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["scenes/showcase.toml", "scenes/gallery/mirror.toml", "scenes/bench/big.toml", "scenes/notes.txt", "scenes/cone.NFF"] {
            write(dir.path(), name, "");
        }
        let manifest = write(
            dir.path(),
            "tests/golden/manifest.toml",
            "[[scenes]]\ndir = \"../../scenes\"\nrecursive = true\nexclude = [\"bench\"]\ngoldens = \".\"\n",
        );
        let suite = Suite::from_manifest(&manifest).unwrap();
        let cases: Vec<(&str, PathBuf)> =
            suite.cases.iter().map(|c| (c.name.as_str(), c.golden.strip_prefix(dir.path()).unwrap().to_path_buf())).collect();
        let expected = ["cone", "gallery-mirror", "showcase"].map(|n| (n, PathBuf::from(format!("tests/golden/./{n}.png"))));
        assert_eq!(cases, expected);
        assert_eq!(suite.name, "manifest");
    }

    #[test]
    fn a_directory_is_its_scene_files_with_goldens_beside_them() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "b.nff", "");
        write(dir.path(), "a.toml", "");
        write(dir.path(), "a.png", "");
        write(dir.path(), "meshes/teapot.obj", "");
        write(dir.path(), ".a.toml.swp.toml", "");
        let suite = Suite::load(dir.path()).unwrap();
        let cases: Vec<(&str, &Path, &Path)> = suite.cases.iter().map(|c| (c.name.as_str(), c.scene.as_path(), c.golden.as_path())).collect();
        assert_eq!(
            cases,
            [
                ("a", dir.path().join("a.toml").as_path(), dir.path().join("a.png").as_path()),
                ("b", dir.path().join("b.nff").as_path(), dir.path().join("b.png").as_path()),
            ]
        );
        assert_eq!(suite.cases[0].criteria, Criteria::for_metric(Metric::Flip));
    }

    #[test]
    fn manifest_errors_name_the_file_and_line() {
        let dir = tempfile::tempdir().unwrap();
        let cases = [
            ("[[case]]\nscene = \"a.toml\"\nrender = { spp = 0 }\n", ":3:", "0 is not in 1..=4096"),
            ("[[case]]\nscene = \"a.toml\"\ncolour = 1\n", ":3:", "unknown field `colour`"),
            ("[compare]\nmetric = \"flip\"\n\n[[case]]\nscene = \"a.toml\"\ngolden = \"a.jpg\"\n", ":4:", "golden:"),
            ("[[scenes]]\ndir = \"nowhere\"\n", ":1:", "dir: cannot read"),
            ("[[case]]\nscene = \"x/a.toml\"\n[[case]]\nscene = \"y/a.nff\"\n", ":3:", "have the same name"),
            ("name = \"empty\"\n", "", "no cases"),
            ("[[case]]\ngolden = \"a.png\"\n", ":1:", "scene: a case needs a `scene` (or an `image` to grade)"),
            ("[[case]]\nscene = \"a.toml\"\npoints = 3\n", ":1:", "points: only a case with an `image` to grade earns points"),
            ("[[case]]\nscene = \"a.toml\"\nvisibility = \"hidden\"\n", ":1:", "visibility: only a case with an `image` to grade is a Gradescope test"),
            ("[[case]]\nimage = \"a.png\"\nscene = \"a.toml\"\nvisibility = \"later\"\n", ":4:", "unknown variant `later`"),
            ("[[case]]\nimage = \"a.png\"\n", ":1:", "image: a graded `image` needs its reference"),
            ("[[case]]\nimage = \"a.png\"\nscene = \"a.toml\"\ngolden = \"a.png\"\n", ":1:", "not both"),
            ("[[case]]\nimage = \"{student}.jpg\"\nscene = \"a.toml\"\n", ":1:", "image: {student}.jpg: use a .png, .ppm, .exr or .pfm file"),
            ("[[case]]\nimage = \"a.png\"\nscene = \"a.toml\"\npoints = 0\n", ":4:", "0 is not a positive finite number"),
            ("[[case]]\nimage = \"a.png\"\nscene = \"a.toml\"\n\n[[case.partial]]\nrmse = 0.1\npoints = 0\n", ":5:", "partial: the case is judged by flip"),
            ("[[case]]\nimage = \"a.png\"\nscene = \"x/a.toml\"\n[[case]]\nimage = \"b.png\"\nscene = \"y/a.toml\"\n", ":4:", "graded cases `a` and `a`"),
        ];
        for (text, place, needle) in cases {
            let manifest = write(dir.path(), "m.toml", text);
            let e = Suite::from_manifest(&manifest).unwrap_err().to_string();
            let prefix = format!("{}{place}", manifest.display());
            assert!(e.starts_with(&prefix) && e.contains(needle), "{text:?}: {e}");
            assert_eq!(e.lines().count(), 1, "{e}");
        }
        let e = Suite::load(&dir.path().join("missing.toml")).unwrap_err().to_string();
        assert!(e.contains("missing.toml: cannot read manifest"), "{e}");
        let empty = tempfile::tempdir().unwrap();
        let e = Suite::load(empty.path()).unwrap_err().to_string();
        assert!(e.ends_with("no scene files (.toml, .nff, .ray or .obj) in the directory"), "{e}");
    }

    #[test]
    fn graded_cases_name_an_image_a_reference_and_points() {
        let dir = tempfile::tempdir().unwrap();
        let manifest = write(
            dir.path(),
            "course.toml",
            r#"
[[case]]
image = "{student}/balls.png"
scene = "spd:balls:1"
points = 10

[[case.partial]]
flip = 0.1
points = 5

[[case]]
name = "room"
image = "room.exr"
golden = "refs/room.exr"
compare = { metric = "psnr" }
visibility = "after_published"
"#,
        );
        let suite = Suite::from_manifest(&manifest).unwrap();
        assert!(suite.cases.is_empty());
        let [balls, room] = &suite.graded[..] else { panic!("{:?}", suite.graded) };
        assert_eq!((balls.name.as_str(), balls.image.as_str()), ("spd-balls-1", "{student}/balls.png"));
        assert_eq!(balls.reference, Reference::Scene("spd:balls:1".into()));
        assert_eq!(balls.scoring, Scoring { points: 10.0, partial: vec![crate::scoring::Band { limit: 0.1, max_bad_fraction: None, points: 5.0 }] });
        assert_eq!(room.reference, Reference::File(dir.path().join("refs/room.exr")));
        assert_eq!((room.criteria.metric, room.scoring.points), (Metric::Psnr, crate::scoring::DEFAULT_POINTS));
        assert_eq!((balls.visibility, room.visibility), (None, Some(Visibility::AfterPublished)));
        let chosen: Vec<&str> = suite.select_graded(&["room".into()]).unwrap().iter().map(|c| c.name.as_str()).collect();
        assert_eq!(chosen, ["room"]);
    }

    #[test]
    fn selecting_cases_keeps_the_suite_order_and_refuses_unknown_names() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["a.toml", "b.toml", "c.toml"] {
            write(dir.path(), name, "");
        }
        let suite = Suite::load(dir.path()).unwrap();
        let chosen: Vec<&str> = suite.select(&["c".into(), "a".into()]).unwrap().iter().map(|c| c.name.as_str()).collect();
        assert_eq!(chosen, ["a", "c"]);
        assert_eq!(suite.select(&[]).unwrap().len(), 3);
        assert!(suite.select(&["d".into()]).unwrap_err().ends_with("no case named `d`"));
    }

    /// The first TOML block after `heading` in docs/golden-ci.md.
    fn documented_toml(heading: &str) -> &'static str {
        let doc = include_str!("../../../docs/golden-ci.md");
        let start = doc.find(heading).and_then(|i| doc[i..].find("```toml\n").map(|j| i + j + 8)).unwrap();
        &doc[start..start + doc[start..].find("```").unwrap()]
    }

    #[test]
    fn the_documented_manifest_is_valid() {
        let text = documented_toml("### A manifest");
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "scenes/gallery/one.toml", "");
        write(dir.path(), "scenes/gallery/big/huge.toml", "");
        write(dir.path(), "scenes/gallery/more/two.nff", "");
        let suite = Suite::from_manifest(&write(dir.path(), "suite.toml", text)).unwrap_or_else(|e| panic!("{e}"));
        let names: Vec<&str> = suite.cases.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["room", "balls", "more-two", "one"]);
        assert_eq!(suite.cases[2].golden, dir.path().join("goldens/more-two.png"));
    }

    #[test]
    fn the_documented_grading_manifest_is_valid() {
        let text = documented_toml("## Autograding");
        let dir = tempfile::tempdir().unwrap();
        let suite = Suite::from_manifest(&write(dir.path(), "course.toml", text)).unwrap_or_else(|e| panic!("{e}"));
        let graded: Vec<(&str, f64)> = suite.graded.iter().map(|c| (c.name.as_str(), c.scoring.points)).collect();
        assert_eq!(graded, [("balls", 10.0), ("room", 5.0)]);
        let bands: Vec<Option<f64>> = suite.graded[0].scoring.partial.iter().map(|b| b.max_bad_fraction).collect();
        assert!(matches!(bands[..], [Some(_), Some(_), None]), "{bands:?}");
        assert_eq!(suite.graded[1].visibility, Some(Visibility::AfterDueDate));
    }

    #[test]
    fn report_file_stems_are_safe() {
        assert_eq!(file_stem_of("a b/c:d"), "a_b_c_d");
        assert_eq!(file_stem_of("ann.lee-2"), "ann.lee-2");
    }
}
