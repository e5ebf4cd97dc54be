//! The kernels' dispatch on the primitive kind, generated from glint-encoding's
//! registry (primitive_kinds.rs), as the prelude's constants are, so that no
//! WGSL file lists the kinds. A file asks for a piece with a line
//! `// generated: NAME`, and the composer puts the piece there (shaders.rs).
//! Each branch is `HAS_X && kind == PRIM_X`, so a kernel's specialisation
//! removes the kinds its scenes lack; a kind the registry lacks falls through
//! every branch: a miss, or a zero normal.

use glint_encoding::primitive_kinds::{Inputs, PrimitiveKind, KINDS};

/// What starts a line that asks for a generated piece.
pub const MARKER: &str = "// generated:";

/// The names a WGSL file can ask for after [`MARKER`].
pub const PIECES: [&str; 3] = ["intersect_prim", "surface_normals", "packet_test"];

/// The piece of WGSL called `name`, or `None` for no such piece.
pub fn piece(name: &str) -> Option<String> {
    match name {
        "intersect_prim" => Some(intersect_prim()),
        "surface_normals" => Some(surface_normals()),
        "packet_test" => Some(packet_test()),
        _ => None,
    }
}

/// The files of the kinds whose functions the piece called `name` calls: every
/// kind's, but the packet test's own four-wide tests are its file's imports.
pub fn files(name: &str) -> Vec<&'static str> {
    KINDS.iter().filter(|k| name != "packet_test" || k.packet_intersect.is_none()).map(|k| k.file).collect()
}

fn is(k: &PrimitiveKind) -> String {
    format!("{} && kind == {}", k.flag, k.code_name)
}

/// The arguments a kind's intersection takes between the primitive and the interval.
fn inputs(k: &PrimitiveKind, ray: &str, frame: &str) -> String {
    match k.inputs {
        Inputs::Ray => ray.to_string(),
        Inputs::Frame => frame.to_string(),
        Inputs::Both => format!("{ray}, {frame}"),
    }
}

/// `if a {…} else if b {…}` at `indent`, from (condition, body) pairs whose
/// bodies are already indented one level deeper.
fn chain(indent: &str, branches: &[(String, String)], otherwise: Option<String>) -> String {
    if branches.is_empty() {
        return otherwise.unwrap_or_default();
    }
    let mut wgsl = String::new();
    for (i, (condition, body)) in branches.iter().enumerate() {
        let keyword = if i == 0 { format!("{indent}if") } else { " else if".to_string() };
        wgsl.push_str(&format!("{keyword} {condition} {{\n{body}{indent}}}"));
    }
    if let Some(body) = otherwise {
        wgsl.push_str(&format!(" else {{\n{body}{indent}}}"));
    }
    wgsl.push('\n');
    wgsl
}

/// `fn intersect_prim`: the closest hit of primitive i in (t_min, t_max).
fn intersect_prim() -> String {
    let mut wgsl = String::from("fn intersect_prim(i: u32, ray: Ray, frame: RayFrame, t_min: f32, t_max: f32) -> f32 {\n");
    wgsl.push_str("    let kind = prim_kind(prim_at(i));\n");
    for k in KINDS {
        wgsl.push_str(&format!("    if {} {{\n", is(k)));
        wgsl.push_str(&format!("        return {}(prim_at(i), {}, t_min, t_max);\n    }}\n", k.intersect, inputs(k, "ray", "frame")));
    }
    wgsl.push_str("    return MISS;\n}\n");
    wgsl
}

/// The statements of `surface_at` that set `geometric` and `shading` for
/// primitive `p` at `point`; kinds of the same normals share a branch.
fn surface_normals() -> String {
    let normals = |k: &PrimitiveKind| {
        let at = if k.normal_at_point { ", point" } else { "" };
        let shading = k.shading_normal.map_or("geometric".to_string(), |f| format!("{f}(p, point)"));
        format!("        geometric = {}(p{at});\n        shading = {shading};\n", k.normal)
    };
    let mut groups: Vec<(Vec<&PrimitiveKind>, String)> = Vec::new();
    for k in KINDS {
        let body = normals(k);
        match groups.iter_mut().find(|(_, b)| *b == body) {
            Some((kinds, _)) => kinds.push(k),
            None => groups.push((vec![k], body)),
        }
    }
    let branches: Vec<(String, String)> = groups
        .into_iter()
        .map(|(kinds, body)| {
            let condition = match kinds.as_slice() {
                [k] => is(k),
                kinds => kinds.iter().map(|k| format!("({})", is(k))).collect::<Vec<_>>().join(" || "),
            };
            (condition, body)
        })
        .collect();
    chain("    ", &branches, None)
}

/// The statements of `packet_test` that set `t`, the four rays' hits on
/// primitive `prim` below `bound`. A kind with a packet test runs it, and a
/// kernel for scenes whose BVH holds that kind alone runs it unasked; the
/// other kinds test the rays one at a time.
fn packet_test() -> String {
    let flags_but = |k: &PrimitiveKind| KINDS.iter().filter(|o| o.code != k.code).map(|o| o.flag).collect::<Vec<_>>().join(" || ");
    let alone = |k: &PrimitiveKind| format!("only_{}", k.flag["HAS_".len()..].to_lowercase());
    let mut wgsl = String::new();
    let mut branches = Vec::new();
    for k in KINDS {
        let Some(intersect4) = k.packet_intersect else { continue };
        let mut condition = is(k);
        if k.bounded {
            wgsl.push_str(&format!("    let {} = !({});\n", alone(k), flags_but(k)));
            condition = format!("{} || ({condition})", alone(k));
        }
        let body = format!("        t = {intersect4}(prim, {}, vec4<f32>(0.0), bound);\n", inputs(k, "p.rays", "p.frame"));
        branches.push((condition, body));
    }
    let one_by_one: Vec<(String, String)> = KINDS
        .iter()
        .filter(|k| k.packet_intersect.is_none())
        .map(|k| (is(k), format!("                t[k] = {}(prim, {}, 0.0, bound[k]);\n", k.intersect, inputs(k, "ray", "ray_frame(ray)"))))
        .collect();
    let rays = (!one_by_one.is_empty()).then(|| {
        let mut body = String::new();
        body.push_str("        // The other kinds one ray at a time (scenes of them trace fast\n");
        body.push_str("        // alone), in a loop whose count the compiler does not know, so that\n");
        body.push_str("        // it keeps one copy of the tests instead of four.\n");
        body.push_str("        var left = 0xfu;\n        while left != 0u {\n");
        body.push_str("            let k = firstTrailingBit(left);\n            left &= left - 1u;\n");
        body.push_str("            let ray = ray_of(p.rays, k);\n");
        body.push_str(&chain("            ", &one_by_one, None));
        body.push_str("        }\n");
        body
    });
    wgsl.push_str(&chain("    ", &branches, rays));
    wgsl
}

#[cfg(test)]
mod tests {
    //! The generated WGSL is run here by a small evaluator of its `if` chains
    //! and `let` flags, for every set of kinds a kernel can be specialised to.
    use std::collections::{BTreeSet, HashMap};

    use glint_encoding::primitive_kinds::{ALL_KINDS, KINDS};

    use super::*;

    /// The statements `wgsl` runs for a primitive of kind `code` in a kernel
    /// specialised to the kinds of `kinds`, with the chains' own lines left out.
    fn run(wgsl: &str, kinds: u32, code: u32) -> Vec<String> {
        let mut values: HashMap<String, bool> = KINDS.iter().map(|k| (k.flag.to_string(), kinds & (1 << k.code) != 0)).collect();
        let lines: Vec<&str> = wgsl.lines().collect();
        let mut ran = Vec::new();
        run_lines(&lines, code, &mut values, &mut ran);
        ran
    }

    fn run_lines(lines: &[&str], code: u32, values: &mut HashMap<String, bool>, ran: &mut Vec<String>) {
        let indent = |line: &str| line.len() - line.trim_start().len();
        let mut i = 0;
        // A `return` ends the function: nothing after it runs.
        while i < lines.len() && !ran.last().is_some_and(|s: &String| s.starts_with("return ")) {
            let line = lines[i].trim();
            let Some(mut condition) = line.strip_prefix("if ").and_then(|l| l.strip_suffix(" {")).map(Some) else {
                if let Some((name, value)) = line.strip_prefix("let only_").and_then(|l| l.strip_suffix(';')?.split_once(" = ")) {
                    let value = eval(value, code, values);
                    values.insert(format!("only_{name}"), value);
                }
                ran.push(line.to_string());
                i += 1;
                continue;
            };
            let mut taken = false;
            loop {
                let end = i + 1 + lines[i + 1..].iter().position(|l| indent(l) == indent(lines[i])).expect("an unclosed branch");
                if !taken && condition.is_none_or(|c| eval(c, code, values)) {
                    run_lines(&lines[i + 1..end], code, values, ran);
                    taken = true;
                }
                i = end;
                match lines[end].trim() {
                    "}" => break,
                    "} else {" => condition = None,
                    other => condition = Some(other.strip_prefix("} else if ").and_then(|l| l.strip_suffix(" {")).expect(other)),
                }
            }
            i += 1;
        }
    }

    /// A condition of flags, `kind == PRIM_X`, `!`, `&&`, `||` and brackets.
    fn eval(condition: &str, code: u32, values: &HashMap<String, bool>) -> bool {
        let spaced = condition.replace('(', " ( ").replace(')', " ) ").replace('!', " ! ");
        let tokens: Vec<&str> = spaced.split_whitespace().collect();
        let (value, rest) = or(&tokens, code, values);
        assert!(rest.is_empty(), "{condition}: {rest:?} left over");
        value
    }

    fn or<'a>(tokens: &'a [&'a str], code: u32, values: &HashMap<String, bool>) -> (bool, &'a [&'a str]) {
        let (mut value, mut rest) = and(tokens, code, values);
        while let ["||", more @ ..] = rest {
            let (next, after) = and(more, code, values);
            (value, rest) = (value | next, after);
        }
        (value, rest)
    }

    fn and<'a>(tokens: &'a [&'a str], code: u32, values: &HashMap<String, bool>) -> (bool, &'a [&'a str]) {
        let (mut value, mut rest) = unary(tokens, code, values);
        while let ["&&", more @ ..] = rest {
            let (next, after) = unary(more, code, values);
            (value, rest) = (value & next, after);
        }
        (value, rest)
    }

    fn unary<'a>(tokens: &'a [&'a str], code: u32, values: &HashMap<String, bool>) -> (bool, &'a [&'a str]) {
        match tokens {
            ["!", rest @ ..] => {
                let (value, rest) = unary(rest, code, values);
                (!value, rest)
            }
            ["(", rest @ ..] => match or(rest, code, values) {
                (value, [")", rest @ ..]) => (value, rest),
                (_, rest) => panic!("an unclosed bracket before {rest:?}"),
            },
            ["kind", "==", name, rest @ ..] => (KINDS.iter().find(|k| k.code_name == *name).expect(name).code == code, rest),
            [name, rest @ ..] => (*values.get(*name).unwrap_or_else(|| panic!("unknown name {name}")), rest),
            [] => panic!("a condition ends early"),
        }
    }

    /// The registry's functions that `statements` call.
    fn calls(statements: &[String]) -> BTreeSet<&'static str> {
        let functions = KINDS.iter().flat_map(|k| [Some(k.intersect), Some(k.normal), k.shading_normal, k.packet_intersect]).flatten();
        functions.filter(|f| statements.iter().any(|s| s.contains(&format!("{f}(")))).collect()
    }

    /// Each kind, in every kernel that holds it, runs its own functions in
    /// every piece, and a kind the registry lacks runs none: a miss, or the
    /// zero normals `surface_at` starts from.
    #[test]
    fn every_kind_runs_its_own_code_in_every_dispatch_and_an_unknown_kind_none() {
        for kinds in 1..=ALL_KINDS {
            for k in KINDS.iter().filter(|k| kinds & (1 << k.code) != 0) {
                let own = |functions: &[Option<&'static str>]| functions.iter().flatten().copied().collect::<BTreeSet<_>>();
                let hit = run(&intersect_prim(), kinds, k.code);
                assert_eq!(calls(&hit), own(&[Some(k.intersect)]), "{} in {kinds:b}", k.code_name);
                assert!(hit.last().is_some_and(|s| s.starts_with(&format!("return {}(", k.intersect))), "{hit:?}");
                assert_eq!(calls(&run(&surface_normals(), kinds, k.code)), own(&[Some(k.normal), k.shading_normal]), "{}", k.code_name);
                let packet = k.packet_intersect.or(Some(k.intersect));
                assert_eq!(calls(&run(&packet_test(), kinds, k.code)), own(&[packet]), "{} in {kinds:b}", k.code_name);
            }
        }
        let unknown = KINDS.len() as u32;
        let missed = run(&intersect_prim(), ALL_KINDS, unknown);
        assert!(calls(&missed).is_empty() && missed.contains(&"return MISS;".to_string()), "{missed:?}");
        for piece in [surface_normals(), packet_test()] {
            assert_eq!(calls(&run(&piece, ALL_KINDS, unknown)), BTreeSet::new(), "{piece}");
        }
    }

    #[test]
    fn a_file_can_ask_for_each_piece_by_name() {
        for name in PIECES {
            assert!(piece(name).is_some_and(|p| !p.is_empty()), "{name}");
        }
        assert_eq!(piece("intersect_disk"), None);
    }
}
