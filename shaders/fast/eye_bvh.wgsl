// The eye rays of a 2×2 block of pixels through the BVH, as one packet: the
// function of lib/eye_block.wgsl when the primary kernel traces packets but
// the scene has no eye tiles.
// import: dispatch eye_rays fast/camera4 fast/packet

fn trace_eye_block(corner: vec2<u32>, live: bool) -> EyeHits {
    // The heat map counts each ray's own visits.
    if dispatch_view() == VIEW_HEATMAP {
        return trace_eye_rays(corner, 0xfu);
    }
    let hit = traverse_packet(packet(camera_rays4(corner)));
    return EyeHits(hit.t, hit.prim, vec4<u32>(0u));
}
