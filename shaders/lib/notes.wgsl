// What the ray tree tells its kernel, ray by ray and term by term: the rays it
// traces, what they hit, and the terms each hit adds (lib/ray_tree.wgsl,
// lib/shade.wgsl, lib/secondary_rays.wgsl call these). Here they record
// nothing and cost nothing; the probe kernel composes its own in their place,
// which records the tree (kernels/probe_notes.wgsl).
// import: bvh primitive types

// A ray of the tree, of kind `kind` (RAY_EYE, RAY_REFLECT or RAY_REFRACT),
// spawned by the ray `parent` noted before, hitting at `t`; returns its id.
fn note_ray(kind: u32, parent: u32, depth: u32, ray: Ray, weight: vec3<f32>, t: f32) -> u32 {
    return NO_RAY;
}
// The surface the ray just noted hit, on primitive `prim`.
fn note_hit(s: Surface, prim: u32) {}
// The ambient term k_a·I_a·O_d at that hit.
fn note_ambient(term: vec3<f32>) {}
// Light `light`'s shadow ray from `point` and the terms it lets through.
fn note_light(light: u32, point: vec3<f32>, dir: vec3<f32>, distance: f32, n_dot_l: f32, shadow: Hit, diffuse: vec3<f32>, specular: vec3<f32>) {}
// The depth cue's scale s_o at that hit.
fn note_cue(scale: f32) {}
// The η refraction used at that hit, and whether the light was totally reflected.
fn note_refraction(eta: f32, total_internal_reflection: bool) {}
