//! Eric Haines' Standard Procedural Databases (SPD 3.14), generated in Rust.
//!
//! Each database is a function of its size that writes the scene through
//! [`Output`], as NFF text, number for number what the original C generator
//! prints in its default mode (`-r 1 -c`: NFF with true curved primitives), or
//! for the seven classic databases as Rayshade text (`-r 8`). Glint reads the
//! NFF with its NFF loader, so `spd:NAME` scenes need no file on disk.

mod fmt_g;
mod nff_out;
mod output;
mod rayshade_out;
mod vecmath;

mod balls;
mod gears;
mod jacks;
mod lattice;
mod mount;
mod nurbtst;
mod rings;
mod shells;
mod sombrero;
mod teapot;
mod tetra;
mod tree;

pub use fmt_g::fmt_g;
pub use nff_out::Nff;
pub use output::Output;
pub use rayshade_out::Rayshade;

/// One of SPD's output formats (its `-r` option).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Format {
    /// `-r 1`, the Neutral File Format.
    #[default]
    Nff,
    /// `-r 8`, Rayshade's `.ray` files.
    Rayshade,
}

/// One of the twelve databases.
pub struct Database {
    pub name: &'static str,
    /// The size the original generator uses without `-s` (the classic benchmark size).
    pub default_size: u32,
    /// The largest size Glint generates (larger ones would not fit in memory or on a device).
    pub max_size: u32,
    generate: fn(u32, &mut dyn Output),
}

/// All twelve, in the order SPD's Readme lists them.
pub const DATABASES: &[Database] = &[
    Database { name: "balls", default_size: 4, max_size: balls::MAX_SIZE, generate: balls::generate },
    Database { name: "gears", default_size: 4, max_size: gears::MAX_SIZE, generate: gears::generate },
    Database { name: "mount", default_size: 6, max_size: mount::MAX_SIZE, generate: mount::generate },
    Database { name: "rings", default_size: 7, max_size: rings::MAX_SIZE, generate: rings::generate },
    Database { name: "teapot", default_size: 6, max_size: teapot::MAX_SIZE, generate: teapot::generate },
    Database { name: "tetra", default_size: 6, max_size: tetra::MAX_SIZE, generate: tetra::generate },
    Database { name: "tree", default_size: 11, max_size: tree::MAX_SIZE, generate: tree::generate },
    Database { name: "jacks", default_size: 1, max_size: jacks::MAX_SIZE, generate: jacks::generate },
    Database { name: "shells", default_size: 5, max_size: shells::MAX_SIZE, generate: shells::generate },
    Database { name: "lattice", default_size: 12, max_size: lattice::MAX_SIZE, generate: lattice::generate },
    Database { name: "sombrero", default_size: 1, max_size: sombrero::MAX_SIZE, generate: sombrero::generate },
    Database { name: "nurbtst", default_size: 1, max_size: nurbtst::MAX_SIZE, generate: nurbtst::generate },
];

/// The seven databases of SPD's benchmark table.
pub const CLASSIC: &[&str] = &["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"];

/// Why a database could not be generated.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SpdError {
    UnknownName(String),
    BadSize { name: &'static str, size: String, max: u32 },
    /// Glint writes Rayshade text for the seven classic databases only: the
    /// others need transforms or height fields that SPD writes to Rayshade
    /// differently from NFF.
    NoRayshade(&'static str),
}

impl std::fmt::Display for SpdError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SpdError::UnknownName(name) => {
                let names: Vec<_> = DATABASES.iter().map(|d| d.name).collect();
                write!(f, "no SPD database named `{name}` (there are: {})", names.join(", "))
            }
            SpdError::BadSize { name, size, max } => {
                write!(f, "SPD {name} has no size `{size}`: a whole number from 1 to {max}")
            }
            SpdError::NoRayshade(name) => write!(
                f,
                "Glint writes SPD {name} as NFF only; the Rayshade format is for the seven classic databases ({})",
                CLASSIC.join(", ")
            ),
        }
    }
}

impl std::error::Error for SpdError {}

/// The database called `name`.
pub fn database(name: &str) -> Result<&'static Database, SpdError> {
    DATABASES.iter().find(|d| d.name == name).ok_or_else(|| SpdError::UnknownName(name.to_string()))
}

impl Database {
    /// The scene at `size` (the default size when `None`) as NFF text.
    pub fn generate(&self, size: Option<u32>) -> Result<String, SpdError> {
        self.generate_as(size, Format::Nff)
    }

    /// The scene at `size` (the default size when `None`) in `format`.
    pub fn generate_as(&self, size: Option<u32>, format: Format) -> Result<String, SpdError> {
        let size = size.unwrap_or(self.default_size);
        if size == 0 || size > self.max_size {
            return Err(SpdError::BadSize { name: self.name, size: size.to_string(), max: self.max_size });
        }
        Ok(match format {
            Format::Nff => {
                let mut out = Nff::new();
                (self.generate)(size, &mut out);
                out.finish()
            }
            Format::Rayshade if !CLASSIC.contains(&self.name) => return Err(SpdError::NoRayshade(self.name)),
            Format::Rayshade => {
                let mut out = Rayshade::new();
                (self.generate)(size, &mut out);
                out.finish()
            }
        })
    }
}

/// `NAME` or `NAME:SIZE`, the part of a `spd:` scene argument after the prefix.
pub fn parse_spec(spec: &str) -> Result<(&'static Database, Option<u32>), SpdError> {
    let (name, size) = match spec.split_once(':') {
        Some((name, size)) => (name, Some(size)),
        None => (spec, None),
    };
    let db = database(name)?;
    let size = match size {
        None => None,
        Some(text) => match text.parse::<u32>() {
            Ok(n) if (1..=db.max_size).contains(&n) => Some(n),
            _ => return Err(SpdError::BadSize { name: db.name, size: text.to_string(), max: db.max_size }),
        },
    };
    Ok((db, size))
}
