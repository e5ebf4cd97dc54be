//! docs/scale-out.md's Slurm recipes, run by a real Slurm: a throwaway
//! single-node cluster (tests/slurm/cluster.sh: munged, slurmctld and slurmd
//! on 127.0.0.1, which `bash .ci/setup --tests` installs) runs the job scripts in
//! docs/scale-out/, the same files the page shows. The stitched still and the
//! frames are, byte for byte, the files of one `glint render`, also after a
//! shard fails and is rerun alone and after a running shard is killed and
//! requeued. A cluster that cannot start fails the tests with its daemons'
//! own messages.

use std::collections::HashMap;
use std::io::{BufRead, BufReader, Read};
use std::net::TcpListener;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{ChildStdin, Command, Stdio};
use std::sync::{mpsc, OnceLock};
use std::time::{Duration, Instant};

/// The longest the tests wait for the cluster or a job, so that a broken
/// cluster fails them rather than hanging CI.
const TIMEOUT: Duration = Duration::from_secs(120);

/// A small image, so that the tests are quick on a software adapter.
const WIDTH: &str = "64";
const HEIGHT: &str = "48";
const SHARDS: &str = "4";

/// The recipes ask for 8 CPUs and 8 GB a task, more than the test node has;
/// options on sbatch's command line override `#SBATCH` lines, as on any
/// cluster smaller than that.
const RESOURCES: [&str; 2] = ["--cpus-per-task=1", "--mem=500M"];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn recipe(name: &str) -> PathBuf {
    repo().join("docs/scale-out").join(name)
}

fn scene(name: &str) -> String {
    repo().join("scenes").join(name).to_str().unwrap().to_string()
}

/// The cluster all tests here submit to, started once. It stops when the test
/// process ends, however it ends, which closes the script's standard input.
struct Cluster {
    _stdin: ChildStdin,
    conf: PathBuf,
}

fn cluster() -> &'static Cluster {
    static CLUSTER: OnceLock<Result<Cluster, String>> = OnceLock::new();
    CLUSTER.get_or_init(start_cluster).as_ref().unwrap_or_else(|e| panic!("{e}"))
}

fn free_port(taken: &mut Vec<TcpListener>) -> String {
    let listener = TcpListener::bind("127.0.0.1:0").expect("a free port on 127.0.0.1");
    let port = listener.local_addr().unwrap().port().to_string();
    taken.push(listener);
    port
}

fn start_cluster() -> Result<Cluster, String> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/slurm/cluster.sh");
    let mut taken = Vec::new();
    let ports = [free_port(&mut taken), free_port(&mut taken)];
    drop(taken);
    let mut child = Command::new("bash")
        .arg(&script)
        .args(&ports)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("{}: cannot run: {e}", script.display()))?;
    let stdout = child.stdout.take().unwrap();
    let (sender, ready) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = sender.send(line);
    });
    match ready.recv_timeout(TIMEOUT) {
        Ok(line) if line.starts_with("ready ") => {
            let conf = Path::new(line["ready ".len()..].trim()).join("slurm.conf");
            Ok(Cluster { _stdin: child.stdin.take().unwrap(), conf })
        }
        _ => {
            // The script stops the daemons it started as it exits.
            let _ = Command::new("kill").arg(child.id().to_string()).status();
            let mut message = String::new();
            let _ = child.stderr.take().unwrap().read_to_string(&mut message);
            let script = script.display();
            Err(format!("the test's Slurm cluster ({script}; `bash .ci/setup --tests` installs slurm-wlm and munge) did not start:\n{message}"))
        }
    }
}

/// A directory jobs are submitted from, as users submit from theirs. The jobs
/// find the `glint` cargo built on PATH behind a stand-in for a node's trouble:
/// while `faults/fail-I` exists, array task I fails; while `faults/hang-I`
/// exists, task I's first run hangs until Slurm kills it.
struct Work {
    dir: tempfile::TempDir,
}

impl Work {
    fn new() -> Work {
        let work = Work { dir: tempfile::tempdir().unwrap() };
        std::fs::create_dir_all(work.path("bin")).unwrap();
        std::fs::create_dir_all(work.path("faults")).unwrap();
        let glint = work.path("bin/glint");
        std::fs::write(
            &glint,
            format!(
                r#"#!/bin/sh
faults={faults}
task=${{SLURM_ARRAY_TASK_ID:-none}}
if [ -e "$faults/fail-$task" ]; then
  echo "the test's glint: task $task fails" >&2
  exit 1
fi
if [ -e "$faults/hang-$task" ] && [ "${{SLURM_RESTART_COUNT:-0}}" = 0 ]; then
  touch "$faults/hanging-$task"
  exec sleep 300
fi
exec {real} "$@"
"#,
                faults = work.path("faults").display(),
                real = env!("CARGO_BIN_EXE_glint"),
            ),
        )
        .unwrap();
        std::fs::set_permissions(&glint, std::fs::Permissions::from_mode(0o755)).unwrap();
        work
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn fault(&self, name: &str, present: bool) {
        let file = self.path("faults").join(name);
        if present {
            std::fs::write(file, "").unwrap();
        } else {
            std::fs::remove_file(file).unwrap();
        }
    }

    /// `program args…` run in this directory against the cluster, with the
    /// recipes' parameters `env`; its standard output, which it must succeed.
    fn run(&self, program: &Path, args: &[&str], env: &[(&str, String)]) -> String {
        let real = Path::new(env!("CARGO_BIN_EXE_glint")).parent().unwrap().to_path_buf();
        let path = std::env::join_paths(
            [self.path("bin"), real].into_iter().chain(std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default())),
        )
        .unwrap();
        let o = Command::new(program)
            .args(args)
            .envs(env.iter().map(|(k, v)| (k, v)))
            .env("SLURM_CONF", &cluster().conf)
            .env("PATH", path)
            .current_dir(self.dir.path())
            .output()
            .unwrap_or_else(|e| panic!("{}: {e}", program.display()));
        let out = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(o.status.success(), "{} {args:?}: {out}{}", program.display(), String::from_utf8_lossy(&o.stderr));
        out
    }

    fn slurm(&self, program: &str, args: &[&str]) -> String {
        self.run(Path::new(program), args, &[])
    }

    /// The recipes' parameters for a small image rendered into `out`.
    fn shards_env(&self) -> Vec<(&'static str, String)> {
        vec![
            ("SCENE", scene("showcase.toml")),
            ("WIDTH", WIDTH.into()),
            ("HEIGHT", HEIGHT.into()),
            ("SHARDS", SHARDS.into()),
            ("OUT", self.path("out/showcase").to_str().unwrap().into()),
        ]
    }

    /// docs/scale-out/submit-shards.sh with `options` for the array: the ids
    /// of the array and of the stitch job.
    fn submit_shards(&self, options: &[&str]) -> (String, String) {
        let args = [&RESOURCES[..], options].concat();
        let out = self.run(&recipe("submit-shards.sh"), &args, &self.shards_env());
        let ids: Vec<String> = out.lines().filter_map(|l| l.split_whitespace().last()).map(String::from).collect();
        assert!(ids.len() == 2 && ids.iter().all(|id| id.parse::<u32>().is_ok()), "submit-shards.sh printed: {out}");
        (ids[0].clone(), ids[1].clone())
    }

    /// The jobs (or array tasks) of `job`, each as its `scontrol show job` fields.
    fn jobs(&self, job: &str) -> Vec<HashMap<String, String>> {
        let out = self.slurm("scontrol", &["show", "job", "--oneliner", job]);
        out.lines()
            .map(|line| line.split_whitespace().filter_map(|f| f.split_once('=')).map(|(k, v)| (k.into(), v.into())).collect())
            .collect()
    }

    /// Waits, at most TIMEOUT, until `done` holds.
    fn wait_until(&self, what: &str, done: &mut dyn FnMut() -> bool) {
        let start = Instant::now();
        while !done() {
            if start.elapsed() > TIMEOUT {
                panic!("{what}: not after {TIMEOUT:?}; the queue:\n{}\n{}", self.slurm("squeue", &[]), self.logs());
            }
            std::thread::sleep(Duration::from_millis(200));
        }
    }

    /// Waits until none of `jobs` is queued or running.
    fn wait_for(&self, jobs: &[&str]) {
        let list = jobs.join(",");
        self.wait_until(&format!("jobs {list} ended"), &mut || self.slurm("squeue", &["-h", "-o", "%i", "-j", &list]).trim().is_empty());
    }

    fn logs(&self) -> String {
        let Ok(entries) = std::fs::read_dir(self.path("logs")) else { return "no logs".into() };
        let mut logs: Vec<String> = entries
            .map(|e| e.unwrap().path())
            .map(|p| format!("{}:\n{}", p.display(), std::fs::read_to_string(&p).unwrap_or_default()))
            .collect();
        logs.sort();
        logs.join("\n")
    }

    /// One `glint render` of the whole image, or of all the frames.
    fn render(&self, scene_name: &str, output: &Path, extra: &[&str]) {
        let scene = scene(scene_name);
        let output = output.to_str().unwrap();
        let args = [&["render", scene.as_str(), "-o", output, "--width", WIDTH, "--height", HEIGHT, "-q"][..], extra].concat();
        let o = Command::new(env!("CARGO_BIN_EXE_glint")).args(&args).output().unwrap();
        assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    }

    /// The stitch job succeeded, said what it wrote, and wrote the file of one render.
    #[track_caller]
    fn assert_stitched_one_render(&self, stitch: &str) {
        assert_states(&self.jobs(stitch), "COMPLETED", self);
        let stitched = self.path("out/showcase.png");
        let log = std::fs::read_to_string(self.path("logs/stitch.log")).unwrap();
        assert_eq!(log, format!("glint: stitched {WIDTH}x{HEIGHT} from {SHARDS} parts -> {}\n", stitched.display()));
        let whole = self.path("whole.png");
        self.render("showcase.toml", &whole, &[]);
        assert_same_file(&whole, &stitched);
    }
}

#[track_caller]
fn assert_same_file(a: &Path, b: &Path) {
    assert!(std::fs::read(a).unwrap() == std::fs::read(b).unwrap(), "{} and {} differ", a.display(), b.display());
}

#[track_caller]
fn assert_states(jobs: &[HashMap<String, String>], want: &str, work: &Work) {
    for job in jobs {
        assert_eq!(job["JobState"], want, "job {} task {:?}:\n{}", job["JobId"], job.get("ArrayTaskId"), work.logs());
    }
}

#[test]
fn shards_stitch_into_one_render_also_after_a_killed_shard_is_requeued() {
    let work = Work::new();
    work.fault("hang-2", true);
    let (array, stitch) = work.submit_shards(&[]);
    // Shard 2's first run hangs, as on a node gone bad; requeue kills it.
    work.wait_until("shard 2 started", &mut || work.path("faults/hanging-2").exists());
    let task = format!("{array}_2");
    work.slurm("scontrol", &["requeue", &task]);
    // Slurm holds a requeued job back for two minutes; the test moves its
    // start to now so as not to wait.
    work.wait_until("shard 2 requeued", &mut || work.jobs(&task)[0]["JobState"] == "PENDING");
    work.slurm("scontrol", &["update", &format!("JobId={task}"), "StartTime=now"]);
    work.wait_for(&[&array, &stitch]);

    let tasks = work.jobs(&array);
    assert_eq!(tasks.len(), 4);
    assert_states(&tasks, "COMPLETED", &work);
    let restarts: Vec<(&str, &str)> = tasks.iter().map(|t| (t["ArrayTaskId"].as_str(), t["Restarts"].as_str())).collect();
    assert_eq!(restarts.iter().filter(|(_, r)| *r != "0").collect::<Vec<_>>(), [&("2", "1")]);
    work.assert_stitched_one_render(&stitch);
}

#[test]
fn a_failed_shard_stops_the_stitch_until_it_is_rerun_alone() {
    let work = Work::new();
    work.fault("fail-1", true);
    let (array, stitch) = work.submit_shards(&[]);
    work.wait_for(&[&array, &stitch]);
    let tasks = work.jobs(&array);
    let failed: Vec<&str> = tasks.iter().filter(|t| t["JobState"] != "COMPLETED").map(|t| t["ArrayTaskId"].as_str()).collect();
    assert_eq!(failed, ["1"], "{}", work.logs());
    let refused = &work.jobs(&stitch)[0];
    assert_eq!((refused["JobState"].as_str(), refused["ExitCode"].as_str()), ("FAILED", "3:0"));
    let log = std::fs::read_to_string(work.path("logs/stitch.log")).unwrap();
    assert_eq!(
        log,
        "glint: the parts leave 768 pixels of the 64x48 image uncovered, the first at (0, 12): \
         shard 1 of 4 is missing: render it again (in a Slurm job array, --array=1)\n"
    );
    assert!(!work.path("out/showcase.png").exists());

    // As the stitch says: shard 1 alone, then the stitch again.
    work.fault("fail-1", false);
    let (array, stitch) = work.submit_shards(&["--array=1"]);
    work.wait_for(&[&array, &stitch]);
    let rerun = work.jobs(&array);
    assert_eq!(rerun.iter().map(|t| t["ArrayTaskId"].as_str()).collect::<Vec<_>>(), ["1"]);
    assert_states(&rerun, "COMPLETED", &work);
    work.assert_stitched_one_render(&stitch);
}

#[test]
fn frame_chunks_are_the_frames_of_one_render() {
    let work = Work::new();
    std::fs::create_dir(work.path("logs")).unwrap();
    let env = [
        ("SCENE", scene("turntable.toml")),
        ("WIDTH", WIDTH.into()),
        ("HEIGHT", HEIGHT.into()),
        ("FRAMES", "5".into()),
        ("CHUNKS", "3".into()),
        ("OUT", work.path("out/turntable").to_str().unwrap().into()),
    ];
    let recipe = recipe("render-frames.sbatch");
    let args = [&["--parsable", "--array=0-2"][..], &RESOURCES, &[recipe.to_str().unwrap()]].concat();
    let array = work.run(Path::new("sbatch"), &args, &env).trim().to_string();
    work.wait_for(&[&array]);
    assert_states(&work.jobs(&array), "COMPLETED", &work);
    work.render("turntable.toml", &work.path("one_%04d.png"), &["--frames", "0..5"]);
    let mut frames: Vec<String> =
        std::fs::read_dir(work.path("out/turntable")).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    frames.sort();
    assert_eq!(frames, (0..5).map(|n| format!("frame_{n:04}.png")).collect::<Vec<_>>());
    for n in 0..5 {
        assert_same_file(&work.path(&format!("one_{n:04}.png")), &work.path(&format!("out/turntable/frame_{n:04}.png")));
    }
}

/// docs/scale-out.md shows each job script, byte for byte, under a link to it.
#[test]
fn the_docs_show_the_job_scripts_the_cluster_runs() {
    let doc = std::fs::read_to_string(repo().join("docs/scale-out.md")).unwrap();
    let mut names: Vec<String> =
        std::fs::read_dir(repo().join("docs/scale-out")).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    assert_eq!(names, ["render-frames.sbatch", "render-shards.sbatch", "submit-shards.sh"]);
    for name in names {
        let link = format!("[`scale-out/{name}`](scale-out/{name})");
        let at = doc.find(&link).unwrap_or_else(|| panic!("docs/scale-out.md does not link {link}"));
        let block = doc[at..].split_once("```sh\n").and_then(|(_, rest)| rest.split_once("\n```")).map(|(block, _)| block);
        let file = std::fs::read_to_string(recipe(&name)).unwrap();
        assert_eq!(block.map(|b| format!("{b}\n")).as_deref(), Some(file.as_str()), "the block after {link} is not the file");
    }
}
