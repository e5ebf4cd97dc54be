// The eye rays of a 2×2 block of pixels through its tile's list
// (crates/glint-encoding/src/eye_tiles.rs; docs/decisions/046-eye-tiles.md): the
// function of lib/eye_block.wgsl for a scene with eye tiles. A SIMD group's lanes trace blocks
// of one tile (the host dispatches so), and walk its list together, nearest
// first: each entry's primitive is loaded by four lanes, a word each, and
// broadcast to all, where lavapipe would load it once per lane, word by word.
// Each ray gets the hit the BVH walk gives it: the same tests (packet_test),
// of every primitive its ray can reach.
// import: bindings dispatch eye_rays fast/camera4 fast/packet types

// Per tile, the index of its first entry and their number; then each tile's
// entries, primitive indices; then, where the last tile's entries end, each
// primitive's distance (f32 bits).
@group(1) @binding(0) var<storage, read> eye_tiles: array<u32>;
// The scene's primitives (binding 1 of group 0) as four words of 16 bytes each.
@group(1) @binding(1) var<storage, read> prim_words: array<vec4<u32>>;

const EYE_TILE = vec2<u32>(EYE_TILE_WIDTH, EYE_TILE_HEIGHT);

// `live`: the block has a pixel in the band; the walk needs not wait for the
// others' rays, which the list is not for.
// The subgroup operations run in uniform control flow because a SIMD group's
// lanes share one tile, so one `count`; no compiler can see that, and WebGPU's
// (Tint) rejects the kernel unless told.
@diagnostic(off, subgroup_uniformity)
fn trace_eye_block(corner: vec2<u32>, live: bool) -> EyeHits {
    // The heat map counts each ray's own visits.
    if dispatch_view() == VIEW_HEATMAP {
        return trace_eye_rays(corner, 0xfu);
    }
    let p = packet(camera_rays4(corner));
    var hit = packet_planes(p);
    // Every lane is active here: the SIMD group's size, and this lane's place in it.
    let lanes = subgroupAdd(1u);
    let lane = subgroupExclusiveAdd(1u);
    // Blocks past the image's edge, which whole workgroups reach, take the
    // edge's tile: they trace nothing the image keeps.
    let tiles = (vec2<u32>(uniforms.width, uniforms.height) + EYE_TILE - 1u) / EYE_TILE;
    let place = min(corner / EYE_TILE, tiles - 1u);
    let tile = place.y * tiles.x + place.x;
    let first = eye_tiles[2u * tile];
    let count = eye_tiles[2u * tile + 1u];
    let last = 2u * (tiles.x * tiles.y - 1u);
    let distances = eye_tiles[last] + eye_tiles[last + 1u];
    for (var k = 0u; k < count; k += lanes) {
        // Each lane loads one of the next `lanes` entries; the walk takes them in turn.
        let entry = first + min(k + lane, count - 1u);
        let listed = eye_tiles[entry];
        let listed_near = bitcast<f32>(eye_tiles[distances + listed]);
        for (var j = 0u; j < min(lanes, count - k); j++) {
            // Nearest first: once every ray has a hit nearer than this entry
            // can be, so has it than every entry after it.
            if subgroupAll(!live || max4(hit.t) < subgroupShuffle(listed_near, j)) {
                return EyeHits(hit.t, hit.prim, vec4<u32>(0u));
            }
            let i = subgroupShuffle(listed, j);
            let word = prim_words[4u * i + (lane & 3u)];
            let a = subgroupBroadcast(word, 0u);
            let b = subgroupBroadcast(word, 1u);
            let c = subgroupBroadcast(word, 2u);
            let rest = subgroupBroadcast(word, 3u);
            let prim = GpuPrim(bitcast<vec4<f32>>(a), bitcast<vec4<f32>>(b), bitcast<vec4<f32>>(c), rest.x, rest.y, rest.z, rest.w);
            hit = packet_test(i, prim, p, hit);
        }
    }
    return EyeHits(hit.t, hit.prim, vec4<u32>(0u));
}
