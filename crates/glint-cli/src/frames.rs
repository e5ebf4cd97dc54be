//! `glint render --frames A..B`: which frames of a scene's `[animation]` to
//! render, the output name of each (`out_%04d.png`), and `--video`, made by
//! ffmpeg from the frames once they are written. Everything here is checked
//! before any rendering starts.

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::process::Command;

use clap::Args;
use glint_scene::Scene;

use crate::{exit, Failure};

#[derive(Args)]
pub struct FrameArgs {
    /// Render frames A to B-1 of the scene's [animation] (the end is excluded;
    /// A.. renders to the last frame, N alone frame N), each to the output
    /// name with the frame number put in for its %d or %04d (out_%04d.png)
    #[arg(long, value_name = "A..B", value_parser = parse_frames)]
    frames: Option<FrameRange>,
    /// Once the frames are written, encode them as this video with ffmpeg,
    /// which must be on PATH (the frames must be whole PNG images)
    #[arg(long, value_name = "VIDEO", requires = "frames")]
    video: Option<PathBuf>,
    /// Frames per second of the --video (default: the animation's fps)
    #[arg(long, requires = "video", value_parser = positive_fps)]
    fps: Option<f32>,
}

/// The frames asked for, before the animation's length is known.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameRange {
    start: u32,
    /// `None`: to the animation's end.
    end: Option<u32>,
}

fn parse_frames(s: &str) -> Result<FrameRange, String> {
    let number = |t: &str| t.trim().parse::<u32>().ok();
    if let Some((a, b)) = s.split_once("..=") {
        let hint = match (number(a), number(b)) {
            (Some(a), Some(b)) => format!(": write {a}..{} for frames {a} to {b}", u64::from(b) + 1),
            _ => String::new(),
        };
        return Err(format!("`{s}`: the end of A..B is excluded, as in Rust, and ..= is not accepted{hint}"));
    }
    let range = match s.split_once("..") {
        None => number(s).map(|n| FrameRange { start: n, end: n.checked_add(1) }),
        Some((a, "")) => number(a).map(|start| FrameRange { start, end: None }),
        Some((a, b)) => number(a).zip(number(b)).map(|(start, end)| FrameRange { start, end: Some(end) }),
    };
    match range {
        Some(FrameRange { start, end: Some(end) }) if end <= start => {
            Err(format!("`{s}` holds no frame: A..B renders frames A to B-1, so B must be above A"))
        }
        Some(range) => Ok(range),
        None => Err(format!("`{s}` is not A..B, A.. or N: give frame numbers from 0, as in 0..48 (frames 0 to 47)")),
    }
}

fn positive_fps(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("`{s}`: the frame rate is a positive number of frames per second, such as 24 or 29.97")),
    }
}

/// An output name with a frame number in it: the text around one `%d` or
/// `%0Nd` (the printf and ffmpeg notation).
#[derive(Debug, Clone, PartialEq)]
struct Pattern {
    before: String,
    digits: usize,
    after: String,
}

impl Pattern {
    /// The pattern in `path`'s file name, if it has one; a `%` that is not a
    /// frame number, two of them, or one in a directory name is an error.
    fn of(path: &Path) -> Result<Option<Pattern>, String> {
        let Some(text) = path.to_str().filter(|t| t.contains('%')) else { return Ok(None) };
        let shown = path.display();
        let at = text.find('%').expect("contains a %");
        let rest = &text[at + 1..];
        let width: String = rest.chars().take_while(char::is_ascii_digit).collect();
        let Some(after) = rest[width.len()..].strip_prefix('d') else {
            return Err(format!("{shown}: a `%` in an output name starts its frame number, written %d or %04d (zero-padded to 4 digits)"));
        };
        if after.contains('%') {
            return Err(format!("{shown}: an output name holds one frame number (%d or %04d), not several"));
        }
        if after.contains(['/', std::path::MAIN_SEPARATOR]) {
            return Err(format!("{shown}: the frame number goes in the file name, not in a directory name"));
        }
        if !(width.is_empty() || width.starts_with('0') && width.len() >= 2) {
            return Err(format!("{shown}: write the frame number as %d or, zero-padded, %0Nd such as %04d"));
        }
        let digits = width.parse::<usize>().unwrap_or(0);
        Ok(Some(Pattern { before: text[..at].to_string(), digits, after: after.to_string() }))
    }

    fn path(&self, frame: u32) -> PathBuf {
        PathBuf::from(format!("{}{frame:0digits$}{}", self.before, self.after, digits = self.digits))
    }
}

/// The frames one `glint render` renders and where each goes.
pub struct FramePlan {
    pub frames: Range<u32>,
    /// Each output name as given, with its frame number pattern if it has one.
    outputs: Vec<(PathBuf, Option<Pattern>)>,
    video: Option<(PathBuf, f32)>,
}

impl FrameArgs {
    /// Checks the frame options against `scene` and the output names and
    /// makes the plan: without --frames, frame 0 (the scene itself, if it is
    /// not animated). `whole` says whether each frame is the whole image.
    pub fn plan(&self, scene: &Scene, outputs: &[&Path], whole: bool) -> Result<FramePlan, Failure> {
        let usage = |m: String| Failure::new(exit::USAGE, m);
        let patterns = outputs
            .iter()
            .map(|p| Pattern::of(p).map(|pattern| (p.to_path_buf(), pattern)))
            .collect::<Result<Vec<_>, _>>()
            .map_err(usage)?;
        let frames = match (self.frames, &scene.animation) {
            (None, _) => {
                if let Some((path, _)) = patterns.iter().find(|(_, p)| p.is_some()) {
                    return Err(usage(format!(
                        "{}: the name has a frame number, but no --frames says which frames to render (as in --frames 0..48)",
                        path.display()
                    )));
                }
                0..1
            }
            (Some(_), None) => {
                return Err(usage("--frames: the scene has no [animation] to take frames from (see docs/scene-format.md)".into()));
            }
            (Some(range), Some(animation)) => {
                let end = range.end.unwrap_or(animation.frames);
                if end > animation.frames || range.start >= end {
                    let asked = match range.end {
                        Some(end) => format!("{}..{end}", range.start),
                        None => format!("{}..", range.start),
                    };
                    return Err(usage(format!(
                        "--frames {asked}: the animation has {} frames, 0..{} (frames 0 to {})",
                        animation.frames,
                        animation.frames,
                        animation.frames - 1
                    )));
                }
                range.start..end
            }
        };
        if frames.len() > 1 {
            if let Some((path, _)) = patterns.iter().find(|(_, p)| p.is_none()) {
                let (stem, ext) =
                    (path.file_stem().unwrap_or_default().to_string_lossy(), path.extension().unwrap_or_default().to_string_lossy());
                return Err(usage(format!(
                    "{}: {} frames need one file each: put the frame number in the name, as in {stem}_%04d.{ext}",
                    path.display(),
                    frames.len()
                )));
            }
        }
        let video = match &self.video {
            None => None,
            Some(video) => {
                check_video(video, &patterns[0], whole)?;
                let fps =
                    self.fps.or(scene.animation.as_ref().map(|a| a.fps)).expect("--video requires --frames, which requires an animation");
                Some((video.clone(), fps))
            }
        };
        Ok(FramePlan { frames, outputs: patterns, video })
    }
}

/// Refuses, before any rendering, a video that cannot be made: no ffmpeg, a
/// part of each frame, frames that are not PNG, or nowhere to write.
fn check_video(video: &Path, (output, _): &(PathBuf, Option<Pattern>), whole: bool) -> Result<(), Failure> {
    let usage = |m: String| Failure::new(exit::USAGE, m);
    if ffmpeg().is_none() {
        return Err(usage(format!(
            "--video {}: making a video needs ffmpeg, which is not on PATH; install it, or leave out --video and encode the frames later",
            video.display()
        )));
    }
    if !whole {
        return Err(usage(
            "--video: a video needs whole frames; render the shards or regions, stitch each frame, then run ffmpeg (docs/scale-out.md)"
                .into(),
        ));
    }
    if !matches!(glint_gpu::Format::from_path(output), Ok(glint_gpu::Format::Png)) {
        return Err(usage(format!("--video: the frames become a video from PNG files, but {} is not one", output.display())));
    }
    let dir = video.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    if !dir.is_dir() || video.is_dir() {
        return Err(Failure::new(
            exit::OUTPUT,
            format!("--video {}: cannot write there (the directory does not exist, or it names a directory)", video.display()),
        ));
    }
    Ok(())
}

/// ffmpeg's place on PATH.
fn ffmpeg() -> Option<PathBuf> {
    let name = if cfg!(windows) { "ffmpeg.exe" } else { "ffmpeg" };
    std::env::split_paths(&std::env::var_os("PATH")?).map(|dir| dir.join(name)).find(|p| p.is_file())
}

impl FramePlan {
    /// Where `output` (an output name as given) goes at `frame`.
    pub fn path(&self, output: &Path, frame: u32) -> PathBuf {
        match self.outputs.iter().find(|(p, _)| p == output) {
            Some((_, Some(pattern))) => pattern.path(frame),
            _ => output.to_path_buf(),
        }
    }

    /// Every file the plan writes, for checking them all before rendering.
    pub fn all_paths(&self) -> impl Iterator<Item = PathBuf> + '_ {
        self.frames.clone().flat_map(move |frame| self.outputs.iter().map(move |(p, _)| self.path(p, frame)))
    }

    /// Encodes the written frames as the --video, if one was asked for: under
    /// a temporary name beside it, renamed into place once ffmpeg succeeds.
    pub fn encode_video(&self, quiet: bool) -> Result<(), Failure> {
        let Some((video, fps)) = &self.video else { return Ok(()) };
        let failed = |m: String| Failure::new(exit::OUTPUT, format!("--video {}: {m}", video.display()));
        let ffmpeg = ffmpeg().ok_or_else(|| failed("ffmpeg is no longer on PATH".into()))?;
        let (output, _) = &self.outputs[0];
        let name = video.file_name().unwrap_or_default().to_string_lossy();
        // ffmpeg picks the container by the extension, so the temporary name keeps it.
        let partial = video.with_file_name(format!(".{name}.partial.{}", video.extension().unwrap_or_default().to_string_lossy()));
        let result = Command::new(&ffmpeg)
            .args(["-nostdin", "-y", "-loglevel", "error", "-framerate", &fps.to_string()])
            .args(["-start_number", &self.frames.start.to_string(), "-i"])
            .arg(output)
            .args(["-frames:v", &self.frames.len().to_string()])
            // Most players need 4:2:0 chroma, which needs even sides.
            .args(["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p"])
            .arg(&partial)
            .output();
        let outcome = match result {
            Err(e) => Err(failed(format!("cannot run {}: {e}", ffmpeg.display()))),
            Ok(o) if !o.status.success() => {
                let text = String::from_utf8_lossy(&o.stderr);
                let last = text.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("no message");
                Err(failed(format!("ffmpeg failed ({}): {}", o.status, last.trim())))
            }
            Ok(_) => std::fs::rename(&partial, video).map_err(|e| failed(e.to_string())),
        };
        if outcome.is_err() {
            let _ = std::fs::remove_file(&partial);
        } else if !quiet {
            eprintln!("glint: encoded {} frames at {fps} fps -> {}", self.frames.len(), video.display());
        }
        outcome
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_ranges_exclude_their_end() {
        assert_eq!(parse_frames("0..4"), Ok(FrameRange { start: 0, end: Some(4) }));
        assert_eq!(parse_frames("12.."), Ok(FrameRange { start: 12, end: None }));
        assert_eq!(parse_frames("7"), Ok(FrameRange { start: 7, end: Some(8) }));
        let inclusive = parse_frames("0..=3").unwrap_err();
        assert!(inclusive.contains("write 0..4 for frames 0 to 3"), "{inclusive}");
        assert!(parse_frames("4..2").unwrap_err().contains("no frame"));
        assert!(parse_frames("3..3").unwrap_err().contains("no frame"));
        for bad in ["", "..", "a..b", "-1..2", "1.5", "..4"] {
            assert!(parse_frames(bad).unwrap_err().contains("is not A..B"), "{bad}");
        }
    }

    #[test]
    fn patterns_put_the_frame_number_in_the_file_name() {
        let p = |s: &str| Pattern::of(Path::new(s));
        assert_eq!(p("out/f_%04d.png").unwrap().unwrap().path(7), PathBuf::from("out/f_0007.png"));
        assert_eq!(p("f%d.exr").unwrap().unwrap().path(12345), PathBuf::from("f12345.exr"));
        assert_eq!(p("f_%03d.png").unwrap().unwrap().path(12345), PathBuf::from("f_12345.png"), "never cut short");
        assert_eq!(p("plain.png").unwrap(), None);
        for (bad, why) in [
            ("f_%s.png", "starts its frame number"),
            ("%d_%d.png", "not several"),
            ("f%04d/x.png", "not in a directory"),
            ("f%4d.png", "zero-padded"),
        ] {
            assert!(p(bad).unwrap_err().contains(why), "{bad}: {:?}", p(bad));
        }
    }
}
