// The eye ray of the pixel an invocation of the primary kernel traces. A
// tuning may put fast/eye_bvh.wgsl or fast/eye_tiles.wgsl in this file's
// place, whose invocations trace 2×2 blocks of pixels as ray packets.
// A seam: this file holds one call of trace_eye_rays (lib/eye_rays.wgsl) only
// so that those files can stand in for it.
// import: eye_rays

// `corner` is the pixel; `live`, whether it is in the band, matters only to
// the eye tiles' walk.
fn trace_eye_block(corner: vec2<u32>, live: bool) -> EyeHits {
    return trace_eye_rays(corner, 1u);
}
