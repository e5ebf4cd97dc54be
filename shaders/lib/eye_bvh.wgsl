// The eye rays of a 2×2 block of pixels through the BVH, as one packet: what
// the primary kernel's import `eye_block` is for a scene without eye tiles.
// import: camera packet

fn trace_eye_block(corner: vec2<u32>, live: bool) -> PacketHit {
    return traverse_packet(packet(camera_rays4(corner)));
}
