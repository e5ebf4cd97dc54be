//! Glint's scene as the kernels read it, with no GPU dependency (Vello's
//! `vello_encoding` is the model): the data layout and the constants host and
//! kernels share, the BVH's encoding, the packing of a scene into plain
//! arrays, the registry of primitive kinds and the scene's half of what a
//! kernel is compiled for. glint-scene holds the model it reads; glint-gpu
//! uploads what it makes.

pub mod eye_tiles;
pub mod gpu_bvh;
pub mod gpu_types;
pub mod primitive_kinds;
mod ray_stats;
pub mod specialization;

pub use ray_stats::RayStats;
