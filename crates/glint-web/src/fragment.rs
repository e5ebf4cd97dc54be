//! A link that shares a view: the URL's fragment names the scene and holds
//! the camera and the samples per pixel, as
//! `#scene=showcase.toml&eye=0,1,4&look=0,0,0&up=0,1,0&fov=40&spp=16`
//! (`ortho=H`, the view plane's height, for an orthographic camera; `spp=1`
//! traces each pixel once, through its centre).

use glam::Vec3;
use glint_scene::{Camera, Projection};

/// What a link's fragment asks for.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    pub scene: String,
    /// The camera, or the scene's own when the link gives none.
    pub camera: Option<Camera>,
    /// Samples per pixel, or the viewer's default.
    pub spp: Option<u32>,
}

/// The fragment (without its `#`) for `scene` seen by `camera` at `spp`
/// samples per pixel.
pub fn encode(scene: &str, camera: &Camera, spp: u32) -> String {
    let v = |v: Vec3| format!("{},{},{}", v.x, v.y, v.z);
    let projection = match camera.projection {
        Projection::Perspective { fov_y_degrees } => format!("fov={fov_y_degrees}"),
        Projection::Orthographic { height } => format!("ortho={height}"),
    };
    format!("scene={scene}&eye={}&look={}&up={}&{projection}&spp={spp}", v(camera.eye), v(camera.look_at), v(camera.up))
}

/// Reads a fragment (with or without its `#`); an empty one asks for nothing.
pub fn decode(fragment: &str) -> Result<Option<Link>, String> {
    let fragment = fragment.trim_start_matches('#');
    if fragment.is_empty() {
        return Ok(None);
    }
    let mut fields = std::collections::HashMap::new();
    for pair in fragment.split('&') {
        let (key, value) = pair.split_once('=').ok_or_else(|| format!("the link's `{pair}` is not KEY=VALUE"))?;
        fields.insert(key, value);
    }
    let scene = fields.get("scene").ok_or("the link names no scene (scene=NAME)")?.to_string();
    let vector = |key: &str| -> Result<Option<Vec3>, String> {
        let Some(text) = fields.get(key) else { return Ok(None) };
        let numbers: Vec<f32> = text.split(',').map(|n| n.parse::<f32>().ok().filter(|n| n.is_finite())).collect::<Option<_>>().unwrap_or_default();
        match numbers[..] {
            [x, y, z] => Ok(Some(Vec3::new(x, y, z))),
            _ => Err(format!("the link's {key}={text} is not three numbers")),
        }
    };
    let number = |key: &str| -> Result<Option<f32>, String> {
        let Some(text) = fields.get(key) else { return Ok(None) };
        text.parse::<f32>().ok().filter(|n| n.is_finite() && *n > 0.0).map(Some).ok_or_else(|| format!("the link's {key}={text} is not a positive number"))
    };
    let spp = match fields.get("spp") {
        None => None,
        Some(text) => Some(text.parse::<u32>().ok().filter(|n| (1..=MAX_SPP).contains(n)).ok_or_else(|| format!("the link's spp={text} is not a whole number from 1 to {MAX_SPP}"))?),
    };
    let projection = match (number("fov")?, number("ortho")?) {
        (Some(fov_y_degrees), None) if fov_y_degrees < 180.0 => Some(Projection::Perspective { fov_y_degrees }),
        (Some(fov), None) => return Err(format!("the link's fov={fov} is not below 180 degrees")),
        (None, Some(height)) => Some(Projection::Orthographic { height }),
        (None, None) => None,
        (Some(_), Some(_)) => return Err("the link gives both fov and ortho".into()),
    };
    let camera = match (vector("eye")?, vector("look")?, vector("up")?, projection) {
        (Some(eye), Some(look_at), Some(up), Some(projection)) => Some(Camera { eye, look_at, up, projection }),
        (None, None, None, None) => None,
        _ => return Err("the link's camera needs all of eye, look, up and fov (or ortho)".into()),
    };
    Ok(Some(Link { scene, camera, spp }))
}

/// The most samples per pixel a link asks for: the viewer's slider's end.
pub const MAX_SPP: u32 = 1024;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_link_gives_back_the_scene_and_camera_it_was_made_from() {
        let cameras = [
            Camera { eye: Vec3::new(0.1, 1.0, 4.5), look_at: Vec3::ZERO, up: Vec3::Y, projection: Projection::Perspective { fov_y_degrees: 40.0 } },
            Camera { eye: Vec3::new(-3.0, 2.0, 1e-7), look_at: Vec3::X, up: Vec3::Z, projection: Projection::Orthographic { height: 2.5 } },
        ];
        for camera in cameras {
            let fragment = encode("spd:teapot", &camera, 4);
            let link = Link { scene: "spd:teapot".into(), camera: Some(camera), spp: Some(4) };
            assert_eq!(decode(&format!("#{fragment}")), Ok(Some(link)), "{fragment}");
        }
    }

    #[test]
    fn a_scene_alone_keeps_its_camera_and_nothing_asks_for_nothing() {
        assert_eq!(decode("#scene=glass.toml"), Ok(Some(Link { scene: "glass.toml".into(), camera: None, spp: None })));
        assert_eq!(decode("#scene=glass.toml&spp=1"), Ok(Some(Link { scene: "glass.toml".into(), camera: None, spp: Some(1) })));
        assert_eq!(decode(""), Ok(None));
        assert_eq!(decode("#"), Ok(None));
    }

    #[test]
    fn a_broken_link_is_one_message() {
        let cases = [
            ("eye=0,0,1", "the link names no scene (scene=NAME)"),
            ("scene=a.toml&eye=0,0", "the link's eye=0,0 is not three numbers"),
            ("scene=a.toml&eye=0,0,1", "the link's camera needs all of eye, look, up and fov (or ortho)"),
            ("scene=a.toml&eye=0,0,1&look=0,0,0&up=0,1,0&fov=-3", "the link's fov=-3 is not a positive number"),
            ("scene=a.toml&eye=0,0,1&look=0,0,0&up=0,1,0&fov=200", "the link's fov=200 is not below 180 degrees"),
            ("scene=a.toml&junk", "the link's `junk` is not KEY=VALUE"),
            ("scene=a.toml&spp=0", "the link's spp=0 is not a whole number from 1 to 1024"),
        ];
        for (fragment, message) in cases {
            assert_eq!(decode(fragment), Err(message.to_string()), "{fragment}");
        }
    }
}
