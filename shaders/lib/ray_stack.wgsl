// The ray tree's stack: WGSL has no recursion, so the rays of Whitted's tree
// still to trace wait here, each with the weight its colour contributes to
// the pixel.
// import: bindings types

struct PendingRay {
    ray: Ray,
    weight: vec3<f32>,
    depth: u32,
    // RAY_EYE, RAY_REFLECT or RAY_REFRACT, and the id `note_ray` gave the ray it came from.
    kind: u32,
    parent: u32,
}

// Where the ray stack's entry `top` is kept. Without transmitters
// (HAS_REFRACTIONS false) a surface spawns its reflected ray alone, so the
// tree is a chain and the stack never holds more than one pending ray: at the
// constant slot 0 it can live in registers (docs/decisions/009-ray-stack-of-the-scenes-depth.md).
fn stack_slot(top: u32) -> u32 {
    return select(0u, top, HAS_REFRACTIONS);
}

// Whether a branch of the tree whose colour would count `weight` times is
// traced: some channel above the cutoff, and above zero.
fn spawns(weight: vec3<f32>) -> bool {
    return any(weight > vec3<f32>(uniforms.cutoff)) && any(weight > vec3<f32>(0.0));
}
