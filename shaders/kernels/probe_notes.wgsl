// The probe kernel's notes (kernels/probe.wgsl): in place of lib/notes.wgsl,
// which records nothing, they record the ray tree ray by ray, with every
// term each ray adds, into the probe buffer that the host reads back
// (glint-gpu/src/probe.rs).
// import: bindings bvh primitive scene_arrays types

// One ray of the tree. Eye, reflected and refracted rays hold what they hit
// and the local terms there; a shadow ray holds its light's terms.
struct ProbeRay {
    origin: vec3<f32>,
    kind: u32,
    dir: vec3<f32>,
    // Index of the ray this one came from; NO_RAY for the eye ray.
    parent: u32,
    // What the ray's colour is multiplied by on its way to the pixel.
    weight: vec3<f32>,
    depth: u32,
    point: vec3<f32>,
    // Distance to the hit along the unit direction; MISS on a miss.
    t: f32,
    geometric: vec3<f32>,
    object: u32,
    shading: vec3<f32>,
    // PROBE_ flags.
    flags: u32,
    // Eye/reflect/refract: k_a·I_a·O_d. Shadow: unused.
    ambient: vec3<f32>,
    // The η used for refraction at the hit (n1/n2).
    eta: f32,
    // Shadow: this light's diffuse term att·S·I_l·k_d·O_d·(N·L).
    diffuse: vec3<f32>,
    n_dot_l: f32,
    // Shadow: this light's specular term.
    specular: vec3<f32>,
    // Shadow: distance to the light.
    distance: f32,
    // Shadow: S, the light let through (0 when blocked).
    transmittance: vec3<f32>,
    light: u32,
    // Depth cue at the hit: s_o (1 without depth cueing).
    cue_scale: f32,
    material: u32,
    // Shadow: the object that blocked the light, NO_RAY when none.
    blocker: u32,
    _pad: u32,
}

struct ProbeBuffer {
    color: vec3<f32>,
    count: u32,
    truncated: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    rays: array<ProbeRay, PROBE_CAPACITY>,
}

@group(1) @binding(0) var<storage, read_write> probe: ProbeBuffer;

var<private> current: u32;

fn next_record() -> u32 {
    if probe.count >= PROBE_CAPACITY {
        probe.truncated = 1u;
        return NO_RAY;
    }
    probe.count += 1u;
    return probe.count - 1u;
}

fn note_ray(kind: u32, parent: u32, depth: u32, ray: Ray, weight: vec3<f32>, t: f32) -> u32 {
    current = next_record();
    if current != NO_RAY {
        var r: ProbeRay;
        r.origin = ray.origin;
        r.kind = kind;
        r.dir = ray.dir;
        r.parent = parent;
        r.weight = weight;
        r.depth = depth;
        r.t = t;
        r.object = NO_RAY;
        r.blocker = NO_RAY;
        r.cue_scale = 1.0;
        r.eta = 1.0;
        probe.rays[current] = r;
    }
    return current;
}

fn note_hit(s: Surface, prim: u32) {
    if current == NO_RAY {
        return;
    }
    probe.rays[current].point = s.point;
    probe.rays[current].geometric = s.geometric;
    probe.rays[current].shading = s.shading;
    probe.rays[current].object = prim_at(prim).object;
    probe.rays[current].material = prim_material(prim_at(prim));
    probe.rays[current].flags |= select(0u, PROBE_BACKFACE, s.backface);
}

fn note_ambient(term: vec3<f32>) {
    if current != NO_RAY {
        probe.rays[current].ambient = term;
    }
}

fn note_light(light: u32, point: vec3<f32>, dir: vec3<f32>, distance: f32, n_dot_l: f32, shadow: Hit, diffuse: vec3<f32>, specular: vec3<f32>) {
    let parent = current;
    let i = next_record();
    if parent == NO_RAY || i == NO_RAY {
        return;
    }
    var r: ProbeRay;
    r.origin = point;
    r.kind = RAY_SHADOW;
    r.dir = dir;
    r.parent = parent;
    r.weight = probe.rays[parent].weight;
    r.depth = probe.rays[parent].depth;
    r.t = shadow.t;
    r.object = NO_RAY;
    r.flags = select(0u, PROBE_SHADOW_TRACED, (uniforms.flags & FLAG_SHADOWS) != 0u)
        | select(0u, PROBE_BLOCKED, all(shadow.transmittance == vec3<f32>(0.0)));
    r.diffuse = diffuse;
    r.n_dot_l = n_dot_l;
    r.specular = specular;
    r.distance = distance;
    r.transmittance = shadow.transmittance;
    r.light = light;
    r.cue_scale = 1.0;
    r.eta = 1.0;
    r.blocker = select(NO_RAY, prim_at(shadow.prim).object, shadow.t != MISS);
    probe.rays[i] = r;
}

fn note_cue(scale: f32) {
    if current != NO_RAY {
        probe.rays[current].cue_scale = scale;
    }
}

fn note_refraction(eta: f32, total_internal_reflection: bool) {
    if current != NO_RAY {
        probe.rays[current].eta = eta;
        probe.rays[current].flags |= select(0u, PROBE_TOTAL_INTERNAL_REFLECTION, total_internal_reflection);
    }
}
