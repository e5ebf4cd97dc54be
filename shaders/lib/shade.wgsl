// The local illumination model, per colour channel:
//   I = k_a·I_a·O_d + Σ_lights att·S·I_l·(k_d·O_d·max(0, N·L) + specular)
// with specular k_s·O_s·(R·V)^n (Phong) or k_s·O_s·(N·H)^n (Blinn-Phong), O_s white
// when the material has none, or Schlick's F(V·H) with a coloured F0 in place
// of k_s·O_s for metallic highlights. S is the shadow term, att the attenuation.
// import: bindings primitive reflect shadow types

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

// `v` points from the surface towards the viewer.
// Each term is also handed to the kernel's `note_ambient` and `note_light`,
// which the probe kernel records and the others ignore.
fn shade(s: Surface, m: GpuMaterial, v: vec3<f32>) -> vec3<f32> {
    var color = m.ka * uniforms.ambient * m.color;
    note_ambient(color);
    for (var i = 0u; i < uniforms.light_count; i++) {
        let light = lights[i];
        var l: vec3<f32>;
        var distance: f32;
        var att = 1.0;
        if light.kind == LIGHT_DIRECTIONAL {
            l = -light.position;
            distance = MISS;
        } else {
            let to_light = light.position - s.point;
            distance = length(to_light);
            l = to_light / distance;
            att = light_attenuation(light, distance);
        }
        let n_dot_l = dot(s.shading, l);
        // A surface facing away from the light gets nothing and casts no shadow ray.
        if n_dot_l <= 0.0 || dot(s.geometric, l) <= 0.0 {
            continue;
        }
        let shadow = light_visibility(s.point, s.geometric, l, distance);
        if all(shadow.transmittance == vec3<f32>(0.0)) {
            note_light(i, s.point, l, distance, n_dot_l, shadow, vec3<f32>(0.0), vec3<f32>(0.0));
            continue;
        }
        let reach = att * shadow.transmittance * light.radiance;
        let diffuse = reach * m.kd * m.color * n_dot_l;
        // Without highlights in the scene (HAS_HIGHLIGHTS false) the term is 0.
        var specular = vec3<f32>(0.0);
        if HAS_HIGHLIGHTS {
            specular = reach * specular_term(m, s.shading, l, v);
        }
        note_light(i, s.point, l, distance, n_dot_l, shadow, diffuse, specular);
        color += diffuse + specular;
    }
    return color;
}

// s_o at distance d: linear from near_scale at `near` to far_scale at `far`.
fn depth_cue_scale(d: f32) -> f32 {
    let dc = uniforms.depth_cue;
    let f = clamp((d - dc.x) / (dc.y - dc.x), 0.0, 1.0);
    return mix(dc.z, dc.w, f);
}
