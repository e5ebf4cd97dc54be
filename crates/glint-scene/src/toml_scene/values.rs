//! The number, point, colour and matrix values of a TOML scene: newtypes
//! that reject NaN, infinity and wrong lengths while the parser still knows
//! where the value stands.

use std::fmt;

use glam::Vec3;
use serde::de::{self, Deserializer, Visitor};
use serde::Deserialize;

/// A finite number.
#[derive(Debug, Clone, Copy)]
pub(super) struct Num(pub(super) f32);

/// Three finite numbers.
#[derive(Debug, Clone, Copy)]
pub(super) struct V3(pub(super) Vec3);

/// Two finite numbers.
#[derive(Debug, Clone, Copy)]
pub(super) struct V2(pub(super) [f32; 2]);

/// A scale: one finite number for all axes, or three.
#[derive(Debug, Clone, Copy)]
pub(super) struct Scale(pub(super) Vec3);

/// A colour: three finite non-negative numbers, or one number for a grey.
#[derive(Debug, Clone, Copy)]
pub(super) struct Rgb(pub(super) Vec3);

fn finite<E: de::Error>(v: f64) -> Result<f32, E> {
    let f = v as f32;
    if f.is_finite() {
        Ok(f)
    } else if v.is_finite() {
        Err(E::custom(format!("expected a finite number, found {v:e} (beyond the range of 32-bit floats)")))
    } else {
        Err(E::custom(format!("expected a finite number, found {v}")))
    }
}

/// Exactly `N` values: serde's fixed-size arrays would silently drop extra
/// elements (`[0, 0, 0, 1]` read as a point).
fn exactly<'de, D: Deserializer<'de>, T: Deserialize<'de>, const N: usize>(d: D, what: &str) -> Result<[T; N], D::Error> {
    let values = Vec::<T>::deserialize(d)?;
    let found = values.len();
    values.try_into().map_err(|_| de::Error::custom(format!("invalid length {found}, expected {what}")))
}

/// A row-major 4×4 matrix of finite numbers.
#[derive(Debug, Clone, Copy)]
pub(super) struct Matrix(pub(super) [[f32; 4]; 4]);

impl<'de> Deserialize<'de> for Matrix {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let rows: [Vec<f64>; 4] = exactly(d, "4 rows of 4 numbers")?;
        let mut m = [[0.0f32; 4]; 4];
        for (row, values) in m.iter_mut().zip(rows) {
            if values.len() != 4 {
                return Err(de::Error::custom(format!("invalid row length {}, expected 4 rows of 4 numbers", values.len())));
            }
            for (slot, v) in row.iter_mut().zip(values) {
                *slot = finite(v)?;
            }
        }
        Ok(Matrix(m))
    }
}

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        finite(f64::deserialize(d)?).map(Num)
    }
}

impl<'de> Deserialize<'de> for V3 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let [x, y, z]: [f64; 3] = exactly(d, "an array of 3 numbers")?;
        Ok(V3(Vec3::new(finite(x)?, finite(y)?, finite(z)?)))
    }
}

impl<'de> Deserialize<'de> for V2 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let [x, y]: [f64; 2] = exactly(d, "an array of 2 numbers")?;
        Ok(V2([finite(x)?, finite(y)?]))
    }
}

/// A table written inline (`key = { … }`). serde's derived structs also take
/// an array of their values in order, which would read `checker = [1, 1, 0]`
/// as a colour of 1 and a size of 1; this takes tables only.
pub(super) struct Inline<T>(pub(super) T);

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Inline<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Tables<T>(std::marker::PhantomData<T>);
        impl<'de, T: Deserialize<'de>> Visitor<'de> for Tables<T> {
            type Value = T;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a table")
            }
            fn visit_map<A: de::MapAccess<'de>>(self, map: A) -> Result<T, A::Error> {
                T::deserialize(de::value::MapAccessDeserializer::new(map))
            }
        }
        d.deserialize_map(Tables(std::marker::PhantomData)).map(Inline)
    }
}

/// Reads one number (for all three components) or three numbers, all finite.
struct SplatOrTriple(&'static str);

impl<'de> Visitor<'de> for SplatOrTriple {
    type Value = Vec3;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Vec3, E> {
        Ok(Vec3::splat(finite(v)?))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Vec3, E> {
        self.visit_f64(v as f64)
    }
    fn visit_seq<A: de::SeqAccess<'de>>(self, mut seq: A) -> Result<Vec3, A::Error> {
        let mut c = [0.0f32; 3];
        for (i, slot) in c.iter_mut().enumerate() {
            let v: f64 = seq.next_element()?.ok_or_else(|| de::Error::invalid_length(i, &self))?;
            *slot = finite(v)?;
        }
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(de::Error::invalid_length(4, &self));
        }
        Ok(Vec3::from(c))
    }
}

impl<'de> Deserialize<'de> for Scale {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(SplatOrTriple("a scale: a number or [sx, sy, sz]")).map(Scale)
    }
}

impl<'de> Deserialize<'de> for Rgb {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let c = d.deserialize_any(SplatOrTriple("a colour: [r, g, b] or a single number"))?;
        if c.min_element() < 0.0 {
            return Err(de::Error::custom("colour components must not be negative"));
        }
        Ok(Rgb(c))
    }
}
