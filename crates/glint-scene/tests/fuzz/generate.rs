//! Structured generators of near-valid files: NFF statements, TOML tables,
//! OBJ and MTL lines, with numbers that are often NaN, infinite, huge, tiny or
//! negative.

use std::fmt;

use proptest::prelude::*;

/// How far from valid a generated file starts out (mutations come on top).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Mode {
    /// Every value in range and every required key there: the file mostly
    /// loads, so mutations reach the checks after parsing.
    Sane,
    /// Numbers often NaN, infinite, huge, tiny, negative or not numbers; keys
    /// missing or where they do not belong.
    Wild,
}

pub(crate) fn decimal(range: std::ops::Range<f64>) -> BoxedStrategy<String> {
    range.prop_map(|v| format!("{v:.3}")).boxed()
}

/// A number as text.
pub(crate) fn number(mode: Mode) -> BoxedStrategy<String> {
    let sane = prop_oneof![3 => decimal(-10.0..10.0), 1 => (-5i64..10).prop_map(|v| v.to_string())];
    match mode {
        Mode::Sane => sane.boxed(),
        Mode::Wild => prop_oneof![
            6 => sane,
            3 => prop::sample::select(vec![
                "0", "-0", "1", "-1", "0.0", "nan", "NaN", "-nan", "inf", "-inf", "+inf", "infinity", "1e39", "-1e39",
                "3e38", "3.4e38", "-3.4e38", "1e30", "1e20", "1e-20", "1e-40", "1e-45", "1e308", "1e309", "100000",
                "16384", "16385", "65536", "4294967296", "18446744073709551616", "-2147483648", "9223372036854775807",
                "1e", "1.2.3", "--1", "+", ".", "0x10", "1_000", "x",
            ])
            .prop_map(String::from),
            1 => any::<f32>().prop_map(|v| v.to_string()),
            1 => any::<f64>().prop_map(|v| format!("{v:e}")),
            1 => any::<i64>().prop_map(|v| v.to_string()),
        ]
        .boxed(),
    }
}

/// A number that should be positive (a radius, a colour component).
pub(crate) fn positive(mode: Mode) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => decimal(0.05..5.0),
        Mode::Wild => number(mode),
    }
}

pub(crate) fn numbers(mode: Mode, n: usize) -> BoxedStrategy<String> {
    prop::collection::vec(number(mode), n).prop_map(|v| v.join(" ")).boxed()
}

pub(crate) fn positives(mode: Mode, n: usize) -> BoxedStrategy<String> {
    prop::collection::vec(positive(mode), n).prop_map(|v| v.join(" ")).boxed()
}

/// `value` with probability `p`, which may be 1 (proptest's own `weighted`
/// wants it below 1).
pub(crate) fn maybe<T: fmt::Debug + Clone + 'static>(p: f64, value: BoxedStrategy<T>) -> BoxedStrategy<Option<T>> {
    if p >= 1.0 { value.prop_map(Some).boxed() } else { prop::option::weighted(p, value).boxed() }
}

/// A generator of a file's text.
pub(crate) type Generator = fn(Mode) -> BoxedStrategy<String>;

/// Either mode's version of a generator.
pub(crate) fn both_modes(generator: Generator) -> BoxedStrategy<String> {
    prop_oneof![generator(Mode::Sane), generator(Mode::Wild)].boxed()
}

/// The presence of an optional field: Sane keeps it or leaves it out, Wild
/// also drops required ones.
pub(crate) fn presence(mode: Mode, required: bool) -> f64 {
    match (mode, required) {
        (Mode::Sane, true) => 1.0,
        (Mode::Wild, true) => 0.95,
        (_, false) => 0.5,
    }
}

// ---------------------------------------------------------------------------
// NFF

pub(crate) fn nff_view(mode: Mode) -> BoxedStrategy<String> {
    let field = move |name: &'static str, value: BoxedStrategy<String>| {
        maybe(presence(mode, name != "hither"), value).prop_map(move |v| v.map(|v| format!("{name} {v}")))
    };
    let resolution = match mode {
        Mode::Sane => (1u32..40, 2u32..40).prop_map(|(w, h)| format!("{w} {h}")).boxed(),
        Mode::Wild => prop_oneof![numbers(mode, 2), (0i64..40, 0i64..40).prop_map(|(w, h)| format!("{w} {h}"))].boxed(),
    };
    let angle = match mode {
        Mode::Sane => decimal(5.0..170.0),
        Mode::Wild => number(mode),
    };
    (
        field("from", prop_oneof![Just("0 0 5".to_string()), numbers(mode, 3)].boxed()),
        field("at", prop_oneof![Just("0 0 0".to_string()), numbers(mode, 3)].boxed()),
        field("up", prop_oneof![Just("0 1 0".to_string()), numbers(mode, 3)].boxed()),
        field("angle", angle),
        field("hither", positive(mode)),
        field("resolution", resolution),
        any::<bool>(),
        prop::sample::select(vec![" ", "\n"]),
    )
        .prop_map(|(a, b, c, d, e, f, reverse, sep)| {
            let mut fields: Vec<String> = [a, b, c, d, e, f].into_iter().flatten().collect();
            if reverse {
                fields.reverse();
            }
            format!("v{sep}{}", fields.join(sep))
        })
        .boxed()
}

pub(crate) fn nff_statement(mode: Mode) -> BoxedStrategy<String> {
    let counted = move |keyword: &'static str, per_vertex: BoxedStrategy<String>| {
        let corners = if mode == Mode::Sane { 3..8 } else { 0..8 };
        (prop::collection::vec(per_vertex, corners), maybe(if mode == Mode::Sane { 1.0 } else { 0.8 }, Just(()).boxed()), 0usize..8)
            .prop_map(move |(vertices, honest, claimed)| {
                let n = if honest.is_some() { vertices.len() } else { claimed };
                format!("{keyword} {n}\n{}", vertices.join("\n"))
            })
    };
    // Vertices of a polygon in a plane z = const, as SPD files mostly have.
    let planar = (number(mode), number(mode), number(mode)).prop_map(|(x, y, _)| format!("{x} {y} 1"));
    let patch_vertex = (numbers(mode, 3), numbers(mode, 3)).prop_map(|(v, n)| format!("{v} {n}"));
    prop_oneof![
        1 => positives(mode, 3).prop_map(|c| format!("b {c}")),
        2 => (numbers(mode, 3), prop::option::of(positives(mode, 3)))
            .prop_map(|(p, c)| format!("l {p} {}", c.unwrap_or_default())),
        2 => (positives(mode, 3), positives(mode, 4), positive(mode)).prop_map(|(c, k, ior)| format!("f {c} {k} {ior}")),
        2 => (numbers(mode, 3), positive(mode), numbers(mode, 3), positive(mode))
            .prop_map(|(b, br, a, ar)| format!("c\n{b} {br}\n{a} {ar}")),
        4 => (numbers(mode, 3), positive(mode)).prop_map(|(c, r)| format!("s {c} {r}")),
        2 => counted("p", planar.boxed()),
        1 => counted("p", numbers(mode, 3)),
        2 => counted("pp", patch_vertex.boxed()),
        1 => "[ -~]{0,20}".prop_map(|c| format!("# {c}")),
    ]
    .boxed()
}

pub(crate) fn nff_text(mode: Mode) -> BoxedStrategy<String> {
    (maybe(presence(mode, true), nff_view(mode)), prop::collection::vec(nff_statement(mode), 0..10), 0usize..10)
        .prop_map(|(view, statements, view_at)| {
            let mut lines = statements;
            if let Some(v) = view {
                let at = view_at.min(lines.len());
                lines.insert(at, v);
            }
            lines.join("\n") + "\n"
        })
        .boxed()
}

// ---------------------------------------------------------------------------
// Rayshade

/// A surface name: Sane files define all three before using them.
fn ray_surface_name() -> BoxedStrategy<String> {
    prop::sample::select(vec!["s0", "s1", "s2"]).prop_map(String::from).boxed()
}

fn ray_surface(mode: Mode, name: BoxedStrategy<String>) -> BoxedStrategy<String> {
    let component = prop_oneof![
        (prop::sample::select(vec!["ambient", "diffuse", "specular", "body"]), positives(mode, 3)).prop_map(|(k, c)| format!("{k} {c}")),
        (prop::sample::select(vec!["specpow", "reflect", "transp", "index", "extinct"]), positive(mode)).prop_map(|(k, v)| format!("{k} {v}")),
        Just("noshadow".to_string()),
    ];
    (name, prop::collection::vec(component, 0..6))
        .prop_map(|(name, components)| format!("surface {name}\n    {}", components.join("\n    ")))
        .boxed()
}

pub(crate) fn ray_statement(mode: Mode) -> BoxedStrategy<String> {
    let surf = ray_surface_name;
    let planar = (number(mode), number(mode)).prop_map(|(x, y)| format!("{x} {y} 1"));
    let smooth_vertex = (numbers(mode, 3), numbers(mode, 3)).prop_map(|(v, n)| format!("{v} {n}"));
    let corners = if mode == Mode::Sane { 3..8 } else { 0..8 };
    prop_oneof![
        1 => numbers(mode, 3).prop_map(|v| format!("eyep {v}")),
        1 => numbers(mode, 3).prop_map(|v| format!("lookp {v}")),
        1 => (positive(mode), prop::option::of(positive(mode))).prop_map(|(h, v)| format!("fov {h} {}", v.unwrap_or_default())),
        1 => positives(mode, 3).prop_map(|c| format!("background {c}")),
        1 => (0u32..16).prop_map(|n| format!("maxdepth {n}")),
        1 => (1u32..4).prop_map(|n| format!("sample {n} nojitter")),
        2 => (positive(mode), numbers(mode, 3)).prop_map(|(i, p)| format!("light {i} point {p}")),
        1 => (positives(mode, 3), numbers(mode, 3)).prop_map(|(i, d)| format!("light {i} directional {d}")),
        1 => positive(mode).prop_map(|i| format!("light {i} ambient")),
        // Sane files define new names; Wild ones also define a name again.
        1 => ray_surface(mode, match mode {
            Mode::Sane => (0u32..1_000_000).prop_map(|n| format!("x{n}")).boxed(),
            Mode::Wild => ray_surface_name(),
        }),
        4 => (surf(), positive(mode), numbers(mode, 3)).prop_map(|(s, r, c)| format!("sphere {s} {r} {c}")),
        2 => (surf(), positive(mode), numbers(mode, 3), positive(mode), numbers(mode, 3))
            .prop_map(|(s, br, b, ar, a)| format!("cone {s} {br} {b}\n{ar} {a}")),
        1 => (surf(), positive(mode), numbers(mode, 6)).prop_map(|(s, r, e)| format!("cylinder {s} {r} {e}")),
        2 => (surf(), prop::collection::vec(planar, corners.clone())).prop_map(|(s, v)| format!("polygon {s}\n{}", v.join("\n"))),
        1 => (surf(), numbers(mode, 9)).prop_map(|(s, v)| format!("triangle {s} {v}")),
        2 => (surf(), prop::collection::vec(smooth_vertex, 3)).prop_map(|(s, v)| format!("triangle {s} {}", v.join("  "))),
        1 => (surf(), numbers(mode, 6)).prop_map(|(s, v)| format!("plane {s} {v}")),
        1 => "[ -~]{0,20}".prop_map(|c| format!("/* {} */", c.replace("*/", ""))),
        1 => "[ -~]{0,20}".prop_map(|c| format!("// {c}")),
    ]
    .boxed()
}

pub(crate) fn ray_text(mode: Mode) -> BoxedStrategy<String> {
    let header = (
        // Near square, so that the default fov of 45 stays below 180 vertically.
        (16u32..40, 16u32..40).prop_map(|(w, h)| format!("screen {w} {h}\neyep 0 -5 1\nlookp 0 0 0\nup 0 0 1")),
        prop::collection::vec(ray_surface(mode, Just(String::new()).boxed()), 3),
    )
        .prop_map(|(view, surfaces)| {
            let defined: Vec<String> = surfaces.iter().enumerate().map(|(i, s)| s.replacen("surface ", &format!("surface s{i}"), 1)).collect();
            format!("{view}\n{}", defined.join("\n"))
        });
    (maybe(presence(mode, true), header.boxed()), prop::collection::vec(ray_statement(mode), 0..10))
        .prop_map(|(header, statements)| header.into_iter().chain(statements).collect::<Vec<_>>().join("\n") + "\n")
        .boxed()
}

// ---------------------------------------------------------------------------
// TOML

/// A TOML number; Wild also gives values of other types.
pub(crate) fn toml_number(mode: Mode) -> BoxedStrategy<String> {
    let spelt = |n: String| match n.as_str() {
        // The TOML spelling, so that they reach the loader.
        "NaN" | "-nan" => "nan".to_string(),
        "infinity" => "inf".to_string(),
        _ => n,
    };
    match mode {
        Mode::Sane => number(mode),
        Mode::Wild => prop_oneof![
            12 => number(mode).prop_map(spelt),
            1 => Just("\"1\"".to_string()),
            1 => Just("[1, 2, 3]".to_string()),
            1 => Just("true".to_string()),
        ]
        .boxed(),
    }
}

pub(crate) fn toml_positive(mode: Mode) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => positive(mode),
        Mode::Wild => toml_number(mode),
    }
}

pub(crate) fn toml_unit(mode: Mode) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => decimal(0.0..1.0),
        Mode::Wild => toml_number(mode),
    }
}

pub(crate) fn toml_array(values: BoxedStrategy<String>, lengths: std::ops::Range<usize>) -> BoxedStrategy<String> {
    prop::collection::vec(values, lengths).prop_map(|v| format!("[{}]", v.join(", "))).boxed()
}

/// Three values; Wild also gives other lengths and bare numbers.
pub(crate) fn toml_triple(mode: Mode, value: fn(Mode) -> BoxedStrategy<String>) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => toml_array(value(mode), 3..4),
        Mode::Wild => prop_oneof![12 => toml_array(value(mode), 3..4), 1 => toml_array(value(mode), 0..6), 1 => value(mode)].boxed(),
    }
}

pub(crate) fn toml_point(mode: Mode) -> BoxedStrategy<String> {
    toml_triple(mode, toml_number)
}

pub(crate) fn toml_colour(mode: Mode) -> BoxedStrategy<String> {
    prop_oneof![4 => toml_triple(mode, toml_unit), 1 => toml_unit(mode)].boxed()
}

/// A string from `valid`; Wild also picks from `invalid`, or a number.
pub(crate) fn toml_choice(mode: Mode, valid: &[&'static str], invalid: &[&'static str]) -> BoxedStrategy<String> {
    let quoted = |choices: Vec<&'static str>| prop::sample::select(choices).prop_map(|s| format!("\"{s}\""));
    match mode {
        Mode::Sane => quoted(valid.to_vec()).boxed(),
        Mode::Wild => prop_oneof![8 => quoted([valid, invalid].concat()), 1 => toml_number(mode)].boxed(),
    }
}

pub(crate) fn toml_bool(mode: Mode) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => any::<bool>().prop_map(|b| b.to_string()).boxed(),
        Mode::Wild => prop_oneof![4 => any::<bool>().prop_map(|b| b.to_string()), 1 => toml_number(mode)].boxed(),
    }
}

/// A key, whether it must be there, and its value.
pub(crate) type Field = (&'static str, bool, BoxedStrategy<String>);

/// A table: `header`, then its fields, each there or not as `mode` has it.
/// Wild also adds a field from `foreign` (keys of other tables) now and then.
pub(crate) fn toml_table(mode: Mode, header: String, fields: Vec<Field>) -> BoxedStrategy<String> {
    let mut lines: Vec<BoxedStrategy<Option<String>>> = fields
        .into_iter()
        .map(|(key, required, value)| {
            maybe(presence(mode, required), value).prop_map(move |v| v.map(|v| format!("{key} = {v}"))).boxed()
        })
        .collect();
    if mode == Mode::Wild {
        let foreign = prop::sample::select(vec!["radius", "center", "path", "fov", "color", "type", "width", "spp", "matrix"]);
        lines.push(prop::option::weighted(0.05, (foreign, toml_number(mode))).prop_map(|f| f.map(|(k, v)| format!("{k} = {v}"))).boxed());
    }
    lines
        .prop_map(move |lines| {
            let body: Vec<String> = lines.into_iter().flatten().collect();
            format!("{header}\n{}\n", body.join("\n"))
        })
        .boxed()
}

pub(crate) fn toml_size(mode: Mode) -> BoxedStrategy<String> {
    match mode {
        Mode::Sane => (1u32..64).prop_map(|v| v.to_string()).boxed(),
        Mode::Wild => prop_oneof![4 => (1i64..64).prop_map(|v| v.to_string()), 1 => toml_number(mode)].boxed(),
    }
}

pub(crate) fn toml_camera(mode: Mode) -> BoxedStrategy<String> {
    let fov = match mode {
        Mode::Sane => decimal(1.0..170.0),
        Mode::Wild => toml_number(mode),
    };
    let eye = prop_oneof![Just("[0, 0, 5]".to_string()), toml_point(mode)].boxed();
    let perspective = toml_table(
        mode,
        "[camera]".into(),
        vec![
            ("type", false, Just("\"perspective\"".to_string()).boxed()),
            ("eye", true, eye.clone()),
            ("look_at", true, prop_oneof![Just("[0, 0, 0]".to_string()), toml_point(mode)].boxed()),
            ("up", false, toml_point(mode)),
            ("fov", true, fov),
        ],
    );
    let orthographic = toml_table(
        mode,
        "[camera]".into(),
        vec![
            ("type", true, toml_choice(mode, &["orthographic"], &["fisheye"])),
            ("eye", true, eye),
            ("look_at", true, Just("[0, 0, 0]".to_string()).boxed()),
            ("height", true, toml_positive(mode)),
        ],
    );
    prop_oneof![3 => perspective, 1 => orthographic].boxed()
}

pub(crate) fn toml_light(mode: Mode) -> BoxedStrategy<String> {
    let common = move || -> Vec<Field> {
        vec![
            ("color", false, toml_colour(mode)),
            ("intensity", false, toml_positive(mode)),
            ("enabled", false, toml_bool(mode)),
        ]
    };
    let point = {
        let mut fields = vec![("type", true, toml_choice(mode, &["point"], &["spot"])), ("position", true, toml_point(mode))];
        fields.extend(common());
        fields.push(("attenuation", false, toml_choice(mode, &["none", "inverse_square"], &["polynomial"])));
        toml_table(mode, "[[light]]".into(), fields)
    };
    let polynomial = {
        let mut fields = vec![
            ("type", true, Just("\"point\"".to_string()).boxed()),
            ("position", true, toml_point(mode)),
            ("attenuation", true, toml_choice(mode, &["polynomial"], &["linear", "none"])),
            ("coefficients", true, toml_triple(mode, toml_positive)),
        ];
        fields.extend(common());
        toml_table(mode, "[[light]]".into(), fields)
    };
    let directional = {
        let mut fields = vec![("type", true, Just("\"directional\"".to_string()).boxed()), ("direction", true, toml_point(mode))];
        fields.extend(common());
        toml_table(mode, "[[light]]".into(), fields)
    };
    prop_oneof![point, polynomial, directional].boxed()
}

pub(crate) fn toml_material(mode: Mode, name: &'static str) -> BoxedStrategy<String> {
    let shininess = match mode {
        Mode::Sane => decimal(0.0..200.0),
        Mode::Wild => toml_number(mode),
    };
    let ior = match mode {
        Mode::Sane => decimal(1.0..2.5),
        Mode::Wild => toml_number(mode),
    };
    // An inline table; Wild also drops a key or adds one that does not belong.
    let checker_keys = (toml_colour(mode), toml_positive(mode));
    let checker = match mode {
        Mode::Sane => checker_keys.prop_map(|(c, s)| format!("{{ color = {c}, size = {s} }}")).boxed(),
        Mode::Wild => (checker_keys, prop::sample::select(vec!["", ", ior = 1", ", colour = 1"]), any::<u8>())
            .prop_map(|((c, s), extra, drop)| match drop % 8 {
                0 => format!("{{ size = {s}{extra} }}"),
                1 => format!("{{ color = {c}{extra} }}"),
                _ => format!("{{ color = {c}, size = {s}{extra} }}"),
            })
            .boxed(),
    };
    toml_table(
        mode,
        format!("[material.{name}]"),
        vec![
            ("color", true, toml_colour(mode)),
            ("ka", false, toml_unit(mode)),
            ("kd", false, toml_unit(mode)),
            ("ks", false, toml_unit(mode)),
            ("shininess", false, shininess),
            ("specular_color", false, toml_colour(mode)),
            ("model", false, toml_choice(mode, &["phong", "blinn"], &["ward"])),
            ("metallic", false, toml_colour(mode)),
            ("reflect", false, toml_colour(mode)),
            ("transmit", false, toml_colour(mode)),
            ("ior", false, ior),
            ("fresnel", false, toml_bool(mode)),
            ("checker", false, checker),
        ],
    )
}

pub(crate) fn toml_object(mode: Mode) -> BoxedStrategy<String> {
    let table = move |kind: BoxedStrategy<String>, mut fields: Vec<Field>| {
        fields.insert(0, ("type", true, kind));
        fields.push(("material", false, toml_choice(mode, &["a"], &["b", "c"])));
        toml_table(mode, "[[object]]".into(), fields)
    };
    let kind = move |kind: &'static str| toml_choice(mode, &[kind], &["torus", "sphere", "mesh"]);
    let planar = (toml_number(mode), toml_number(mode)).prop_map(|(x, y)| format!("[{x}, {y}, 1]"));
    let sphere = table(kind("sphere"), vec![("center", true, toml_point(mode)), ("radius", true, toml_positive(mode))]);
    let triangle = table(
        kind("triangle"),
        vec![
            ("vertices", true, toml_array(toml_point(mode), 3..4)),
            ("normals", false, toml_array(toml_point(mode), 3..4)),
        ],
    );
    let sides = if mode == Mode::Sane { 2..3 } else { 0..4 };
    let plane = table(
        kind("plane"),
        vec![
            ("point", true, toml_point(mode)),
            ("normal", true, toml_point(mode)),
            ("size", false, toml_array(toml_positive(mode), sides)),
        ],
    );
    let corners = if mode == Mode::Sane { 3..8 } else { 0..8 };
    let polygon = table(kind("polygon"), vec![("vertices", true, toml_array(planar.boxed(), corners))]);
    // A cylinder's apex radius defaults to its base radius; a cone needs one.
    let cone = |kind_name: &'static str, apex_radius_required: bool| {
        table(
            kind(kind_name),
            vec![
                ("base", true, toml_point(mode)),
                ("base_radius", true, toml_positive(mode)),
                ("apex", true, toml_point(mode)),
                ("apex_radius", apex_radius_required, toml_positive(mode)),
            ],
        )
    };
    let scale = prop_oneof![toml_positive(mode), toml_triple(mode, toml_positive)].boxed();
    let rows = match mode {
        Mode::Sane => (toml_number(mode), toml_number(mode), toml_number(mode))
            .prop_map(|(x, y, z)| format!("[[1, 0, 0, {x}], [0, 2, 0, {y}], [0, 0, 1, {z}], [0, 0, 0, 1]]"))
            .boxed(),
        Mode::Wild => toml_array(toml_array(toml_number(mode), 3..5), 3..5),
    };
    let path = toml_choice(mode, &["cube.obj", "flat.obj"], &["missing.obj", "part.nff", ".", "cube.mtl"]);
    let mesh = table(
        kind("mesh"),
        vec![
            ("path", true, path.clone()),
            ("translate", false, toml_point(mode)),
            ("rotate", false, toml_point(mode)),
            ("scale", false, scale),
        ],
    );
    let mesh_matrix = table(kind("mesh"), vec![("path", true, path), ("matrix", true, rows)]);
    // Few subdivisions: 10 would make 20 million triangles a case.
    let subdivisions = match mode {
        Mode::Sane => (0u32..3).prop_map(|v| v.to_string()).boxed(),
        Mode::Wild => prop::sample::select(vec!["0", "1", "-1", "11", "1.5", "4294967296", "\"2\"", "nan"]).prop_map(String::from).boxed(),
    };
    let icosphere = table(
        kind("icosphere"),
        vec![
            ("center", true, toml_point(mode)),
            ("radius", true, toml_positive(mode)),
            ("subdivisions", true, subdivisions),
            ("displacement", false, if mode == Mode::Sane { decimal(0.0..0.5) } else { toml_number(mode) }),
        ],
    );
    prop_oneof![
        3 => sphere,
        2 => triangle,
        2 => polygon,
        2 => plane,
        1 => cone("cone", true),
        1 => cone("cylinder", false),
        2 => mesh,
        1 => mesh_matrix,
        1 => icosphere,
    ]
    .boxed()
}

pub(crate) fn toml_text(mode: Mode) -> BoxedStrategy<String> {
    let image = toml_table(
        mode,
        "[image]".into(),
        vec![("width", true, toml_size(mode)), ("height", true, toml_size(mode)), ("background", false, toml_colour(mode))],
    );
    let ambient = toml_table(mode, "[ambient]".into(), vec![("color", false, toml_colour(mode)), ("intensity", false, toml_positive(mode))]);
    let max_depth = match mode {
        Mode::Sane => (1u32..=16).prop_map(|v| v.to_string()).boxed(),
        Mode::Wild => toml_number(mode),
    };
    let render = toml_table(
        mode,
        "[render]".into(),
        vec![
            ("max_depth", false, max_depth),
            ("cutoff", false, toml_unit(mode)),
            ("shadows", false, toml_bool(mode)),
            ("shadow_mode", false, toml_choice(mode, &["opaque", "tinted"], &["soft"])),
            ("reflections", false, toml_bool(mode)),
            ("refractions", false, toml_bool(mode)),
        ],
    );
    let (near, far) = match mode {
        Mode::Sane => (decimal(0.0..5.0), decimal(5.5..50.0)),
        Mode::Wild => (toml_number(mode), toml_number(mode)),
    };
    let depth_cue = toml_table(
        mode,
        "[depth_cue]".into(),
        vec![
            ("color", true, toml_colour(mode)),
            ("near", true, near),
            ("far", true, far),
            ("near_scale", false, toml_unit(mode)),
            ("far_scale", true, toml_unit(mode)),
        ],
    );
    let include = toml_table(mode, "[[include]]".into(), vec![("path", true, toml_choice(mode, &["part.nff"], &["bad.nff", "missing.nff", "cube.obj"]))]);
    (
        image,
        toml_camera(mode),
        prop::option::of(ambient),
        prop::option::of(render),
        prop::option::weighted(0.2, depth_cue),
        prop::collection::vec(toml_light(mode), 0..3),
        toml_material(mode, "a"),
        prop::option::of(toml_material(mode, "b")),
        prop::collection::vec(toml_object(mode), 0..5),
        prop::collection::vec(include, 0..2),
    )
        .prop_map(|(image, camera, ambient, render, depth_cue, lights, a, b, objects, includes)| {
            let mut tables = vec![image, camera];
            tables.extend(ambient);
            tables.extend(render);
            tables.extend(depth_cue);
            tables.extend(lights);
            tables.push(a);
            tables.extend(b);
            tables.extend(objects);
            tables.extend(includes);
            tables.join("\n")
        })
        .boxed()
}

// ---------------------------------------------------------------------------
// OBJ and MTL

/// A face or line vertex: `v`, `v/vt`, `v//vn` or `v/vt/vn`. Sane indices name
/// the four positions, one texture coordinate and one normal every file starts with.
pub(crate) fn obj_reference(mode: Mode) -> BoxedStrategy<String> {
    let (v, other): (BoxedStrategy<i64>, BoxedStrategy<i64>) = match mode {
        Mode::Sane => (prop_oneof![1i64..=4, -4i64..=-1].boxed(), Just(1i64).boxed()),
        Mode::Wild => {
            let wild = || prop_oneof![8 => 1i64..9, 2 => -9i64..0, 1 => Just(0i64), 1 => any::<i64>()].boxed();
            (wild(), wild())
        }
    };
    (v, prop::option::of(other.clone()), prop::option::of(other))
        .prop_map(|(v, vt, vn)| match (vt, vn) {
            (None, None) => v.to_string(),
            (Some(t), None) => format!("{v}/{t}"),
            (None, Some(n)) => format!("{v}//{n}"),
            (Some(t), Some(n)) => format!("{v}/{t}/{n}"),
        })
        .boxed()
}

pub(crate) fn obj_text(mode: Mode) -> BoxedStrategy<String> {
    let position = match mode {
        Mode::Sane => prop_oneof![4 => numbers(mode, 3), 1 => (numbers(mode, 3), positive(mode)).prop_map(|(v, w)| format!("{v} {w}"))].boxed(),
        Mode::Wild => prop_oneof![8 => numbers(mode, 3), 1 => numbers(mode, 4), 1 => numbers(mode, 6), 1 => (0usize..8).prop_flat_map(move |n| numbers(mode, n))].boxed(),
    };
    let vertices = match mode {
        Mode::Sane => 3..7,
        Mode::Wild => 0..7,
    };
    let line = prop_oneof![
        6 => position.prop_map(|v| format!("v {v}")),
        1 => numbers(mode, 2).prop_map(|v| format!("vt {v}")),
        2 => numbers(mode, 3).prop_map(|v| format!("vn {v}")),
        8 => prop::collection::vec(obj_reference(mode), vertices).prop_map(|r| format!("f {}", r.join(" "))),
        1 => prop::collection::vec(obj_reference(mode), 2..4).prop_map(|r| format!("l {}", r.join(" "))),
        1 => prop::sample::select(vec!["o part", "g group", "usemtl a", "usemtl b", "s off", "o"]).prop_map(String::from),
        1 => "[ -~]{0,20}".prop_map(|c| format!("# {c}")),
    ];
    (
        prop::sample::select(if mode == Mode::Sane { vec!["mtllib m.mtl\n", ""] } else { vec!["mtllib m.mtl\n", "mtllib missing.mtl\n", "mtllib\n", ""] }),
        prop::collection::vec(line, 0..14),
    )
        .prop_map(move |(mtllib, lines)| {
            // Sane files have a face to frame for sure.
            let face = if mode == Mode::Sane { "f 1 2 3\n" } else { "" };
            format!("{mtllib}v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\n{face}{}\n", lines.join("\n"))
        })
        .boxed()
}

pub(crate) fn mtl_text(mode: Mode) -> BoxedStrategy<String> {
    let colour = match mode {
        Mode::Sane => prop_oneof![4 => positives(mode, 3), 1 => positive(mode)].boxed(),
        Mode::Wild => prop_oneof![6 => numbers(mode, 3), 2 => numbers(mode, 1), 1 => (0usize..5).prop_flat_map(move |n| numbers(mode, n))].boxed(),
    };
    let scalar = match mode {
        Mode::Sane => positive(mode),
        Mode::Wild => prop_oneof![6 => numbers(mode, 1), 1 => (0usize..3).prop_flat_map(move |n| numbers(mode, n))].boxed(),
    };
    let illum = match mode {
        Mode::Sane => (0u32..11).prop_map(|v| v.to_string()).boxed(),
        Mode::Wild => prop_oneof![(-2i64..12).prop_map(|v| v.to_string()), number(mode)].boxed(),
    };
    let line = prop_oneof![
        1 => prop::sample::select(vec!["newmtl a", "newmtl b"]).prop_map(String::from),
        6 => (prop::sample::select(vec!["Ka", "Kd", "Ks", "Ke", "Tf"]), colour).prop_map(|(k, v)| format!("{k} {v}")),
        4 => (prop::sample::select(vec!["Ns", "Ni", "d", "Tr"]), scalar).prop_map(|(k, v)| format!("{k} {v}")),
        2 => illum.prop_map(|v| format!("illum {v}")),
        1 => prop::sample::select(if mode == Mode::Sane {
            vec!["map_Kd tex.png", "# a comment", "Pr 0.5"]
        } else {
            vec!["map_Kd tex.png", "map_Kd", "bump", "d -halo 0.5", "Kd spectral x.rfl", "newmtl"]
        })
        .prop_map(String::from),
    ];
    prop::collection::vec(line, 0..10).prop_map(|lines| format!("newmtl a\n{}\n", lines.join("\n"))).boxed()
}
