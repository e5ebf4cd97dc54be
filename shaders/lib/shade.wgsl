// The local illumination model, per colour channel:
//   I = k_a·I_a·O_d + Σ_lights att·S·I_l·(k_d·O_d·max(0, N·L) + specular)
// with specular k_s·O_s·(R·V)^n (Phong) or k_s·O_s·(N·H)^n (Blinn-Phong), O_s white
// when the material has none, or Schlick's F(V·H) with a coloured F0 in place
// of k_s·O_s for metallic highlights. S is the shadow term, att the attenuation.
// The sum is taken one light at a time (`light_term`), since S comes from a
// shadow ray that the ray tree traces in between (lib/ray_tree.wgsl).
// import: bindings bvh notes primitive reflect types

fn light_attenuation(light: GpuLight, d: f32) -> f32 {
    // A kernel for a scene whose lights do not fade (HAS_ATTENUATION false,
    // specialization.rs) compiles without the falloff.
    if !HAS_ATTENUATION {
        return 1.0;
    }
    switch light.attenuation {
        case ATTENUATION_INVERSE_SQUARE: { return 1.0 / (d * d); }
        case ATTENUATION_POLYNOMIAL: {
            let c = light.coefficients;
            return min(1.0 / (c.x + c.y * d + c.z * d * d), 1.0);
        }
        default: { return 1.0; }
    }
}

fn specular_term(m: GpuMaterial, n: vec3<f32>, l: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    let h = normalize(l + v);
    var cos_a: f32;
    if (m.flags & MATERIAL_BLINN) != 0u {
        cos_a = dot(n, h);
    } else {
        cos_a = dot(reflect_dir(-l, n), v);
    }
    // pow(0, 0) is undefined in WGSL: a lobe facing away is 0 for every n.
    let lobe = select(0.0, pow(cos_a, m.shininess), cos_a > 0.0);
    if (m.flags & MATERIAL_METALLIC) != 0u {
        return schlick(m.f0, dot(v, h)) * lobe;
    }
    return m.ks * m.specular_color * lobe;
}

// The surface as its lighting sees it. The lecture turns both normals towards
// the eye (surface_at); grading's diagnosis alone (HAS_UNTURNED_NORMALS)
// renders a student's lighting with the normals the geometry gives, which lights
// a back face from behind. Applied twice, it gives `s` back.
fn lit_surface(s: Surface) -> Surface {
    if HAS_UNTURNED_NORMALS && s.backface && (uniforms.flags & FLAG_UNTURNED_NORMALS) != 0u {
        return Surface(s.point, -s.geometric, -s.shading, s.backface);
    }
    return s;
}

// A light as the surface point sees it: the unit direction L towards it, its
// distance (MISS for a directional light), att and N·L.
struct LightSample {
    l: vec3<f32>,
    distance: f32,
    attenuation: f32,
    n_dot_l: f32,
}

fn light_sample(light: GpuLight, s: Surface) -> LightSample {
    if light.kind == LIGHT_DIRECTIONAL {
        return LightSample(-light.position, MISS, 1.0, dot(s.shading, -light.position));
    }
    let to_light = light.position - s.point;
    let distance = length(to_light);
    let l = to_light / distance;
    return LightSample(l, distance, light_attenuation(light, distance), dot(s.shading, l));
}

// The first light from index `first` on that lights `s` (index light_count
// when none does), and how `s` sees it. A surface facing away from a light
// gets nothing from it and casts no shadow ray towards it.
struct LitLight {
    index: u32,
    sample: LightSample,
}

fn next_lit_light(s: Surface, first: u32) -> LitLight {
    var i = first;
    while i < uniforms.light_count {
        let sample = light_sample(lights[i], s);
        if sample.n_dot_l > 0.0 && dot(s.geometric, sample.l) > 0.0 {
            return LitLight(i, sample);
        }
        i++;
    }
    return LitLight(i, LightSample(vec3<f32>(0.0), MISS, 0.0, 0.0));
}

// k_a·I_a·O_d, handed to `note_ambient` (lib/notes.wgsl).
fn ambient_term(m: GpuMaterial) -> vec3<f32> {
    let color = m.ka * uniforms.ambient * m.color;
    note_ambient(color);
    return color;
}

// A lit light's diffuse and specular terms at `s` seen from `v` (pointing
// from the surface towards the viewer), through `shadow`, what its shadow ray
// let through; handed to `note_light` (lib/notes.wgsl).
fn light_term(lit: LitLight, s: Surface, m: GpuMaterial, v: vec3<f32>, shadow: Hit) -> vec3<f32> {
    let i = lit.index;
    let sample = lit.sample;
    let light = lights[i];
    if all(shadow.transmittance == vec3<f32>(0.0)) {
        note_light(i, s.point, sample.l, sample.distance, sample.n_dot_l, shadow, vec3<f32>(0.0), vec3<f32>(0.0));
        return vec3<f32>(0.0);
    }
    let reach = sample.attenuation * shadow.transmittance * light.radiance;
    let diffuse = reach * m.kd * m.color * sample.n_dot_l;
    // Without highlights in the scene (HAS_HIGHLIGHTS false) the term is 0.
    var specular = vec3<f32>(0.0);
    if HAS_HIGHLIGHTS {
        specular = reach * specular_term(m, s.shading, sample.l, v);
    }
    note_light(i, s.point, sample.l, sample.distance, sample.n_dot_l, shadow, diffuse, specular);
    return diffuse + specular;
}

// s_o at distance d: linear from near_scale at `near` to far_scale at `far`.
fn depth_cue_scale(d: f32) -> f32 {
    let dc = uniforms.depth_cue;
    let f = clamp((d - dc.x) / (dc.y - dc.x), 0.0, 1.0);
    return mix(dc.z, dc.w, f);
}
