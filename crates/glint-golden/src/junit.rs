//! JUnit XML, the report format CI systems (GitHub Actions reporters, GitLab's
//! `artifacts:reports:junit`, Jenkins) read: one `testsuite` holding one
//! `testcase` per case, with a `failure` element on each that failed. No
//! timings are written, so a re-run writes the same bytes.

use std::fmt::Write;

use crate::markup::escape;
use crate::runner::{Outcome, Status, Summary};

/// One `testsuite` named `suite_name`.
pub fn junit_xml(suite_name: &str, outcomes: &[Outcome]) -> String {
    junit_xml_suites(suite_name, &[(suite_name, outcomes)])
}

/// One `testsuite` per named list of outcomes (a graded run's students),
/// all in a `testsuites` named `name`.
pub fn junit_xml_suites(name: &str, suites: &[(&str, &[Outcome])]) -> String {
    let all: Vec<&Outcome> = suites.iter().flat_map(|(_, outcomes)| outcomes.iter()).collect();
    let failures = all.iter().filter(|o| o.status.failed()).count();
    let mut xml = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(xml, "<testsuites name=\"{}\" tests=\"{}\" failures=\"{failures}\" errors=\"0\">", escape(name), all.len());
    for (suite_name, outcomes) in suites {
        testsuite(&mut xml, suite_name, outcomes);
    }
    xml.push_str("</testsuites>\n");
    xml
}

fn testsuite(xml: &mut String, suite_name: &str, outcomes: &[Outcome]) {
    let summary = Summary::of(outcomes);
    let name = escape(suite_name);
    let classname = escape(&format!("glint.{suite_name}"));
    let (tests, failures) = (outcomes.len(), summary.failed);
    let _ = writeln!(xml, "  <testsuite name=\"{name}\" tests=\"{tests}\" failures=\"{failures}\" errors=\"0\" skipped=\"0\">");
    for outcome in outcomes {
        let case = escape(&outcome.name);
        let kind = match outcome.status {
            Status::Passed | Status::Blessed => None,
            Status::Mismatch => Some("mismatch"),
            Status::NoGolden => Some("no-golden"),
            Status::NoImage => Some("no-image"),
            Status::Error => Some("error"),
        };
        match kind {
            None => {
                let _ = writeln!(xml, "    <testcase name=\"{case}\" classname=\"{classname}\"/>");
            }
            Some(kind) => {
                let detail = escape(&outcome.detail);
                let _ = writeln!(xml, "    <testcase name=\"{case}\" classname=\"{classname}\">");
                let _ = writeln!(xml, "      <failure type=\"{kind}\" message=\"{detail}\">{}</failure>", escape(&outcome.explanation()));
                let _ = writeln!(xml, "    </testcase>");
            }
        }
    }
    xml.push_str("  </testsuite>\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use quick_xml::events::Event;

    fn outcome(name: &str, status: Status, detail: &str) -> Outcome {
        Outcome {
            name: name.into(),
            file_stem: name.into(),
            files: vec![("scene", format!("scenes/{name}.toml").into()), ("golden", format!("goldens/{name}.png").into())],
            settings: Some("view shaded, max depth 5, 1 spp, 64x48".into()),
            status,
            detail: detail.into(),
            points: None,
            images: None,
            diagnosis: None,
        }
    }

    /// An element as parsed: its name, its attributes, and the index of the
    /// element it is in.
    #[derive(Debug)]
    struct Element {
        name: String,
        attributes: Vec<(String, String)>,
        parent: Option<usize>,
    }

    fn parse(xml: &str) -> Vec<Element> {
        let mut reader = quick_xml::Reader::from_str(xml);
        let mut elements = Vec::new();
        let mut open: Vec<usize> = Vec::new();
        loop {
            let (start, empty) = match reader.read_event().unwrap() {
                Event::Start(e) => (e, false),
                Event::Empty(e) => (e, true),
                Event::End(_) => {
                    open.pop();
                    continue;
                }
                Event::Eof => break,
                _ => continue,
            };
            let attributes = start
                .attributes()
                .map(|a| {
                    let a = a.unwrap();
                    (String::from_utf8(a.key.as_ref().to_vec()).unwrap(), a.normalized_value(quick_xml::XmlVersion::Implicit1_0).unwrap().into_owned())
                })
                .collect();
            let name = String::from_utf8(start.name().as_ref().to_vec()).unwrap();
            elements.push(Element { name, attributes, parent: open.last().copied() });
            if !empty {
                open.push(elements.len() - 1);
            }
        }
        assert!(open.is_empty(), "unclosed elements");
        elements
    }

    #[test]
    fn the_schemas_required_elements_are_there() {
        let outcomes = [
            outcome("good", Status::Passed, "flip 0 <= 0.01"),
            outcome("bad <&>", Status::Mismatch, "flip 0.5 > 0.01, \"quoted\""),
            outcome("new", Status::NoGolden, "no golden: goldens/new.png"),
            outcome("blessed", Status::Blessed, "wrote goldens/blessed.png"),
        ];
        let xml = junit_xml("course", &outcomes);
        let elements = parse(&xml);
        let attribute = |e: &Element, key: &str| e.attributes.iter().find(|(k, _)| k == key).map(|(_, v)| v.clone());
        assert_eq!(elements[0].name, "testsuites");
        let suite = &elements[1];
        assert_eq!(suite.name, "testsuite");
        assert_eq!(attribute(suite, "name").as_deref(), Some("course"));
        assert_eq!(attribute(suite, "tests").as_deref(), Some("4"));
        assert_eq!(attribute(suite, "failures").as_deref(), Some("2"));
        let cases: Vec<&Element> = elements.iter().filter(|e| e.name == "testcase").collect();
        assert_eq!(cases.len(), 4);
        for case in &cases {
            assert!(attribute(case, "name").is_some() && attribute(case, "classname").as_deref() == Some("glint.course"), "{case:?}");
        }
        assert_eq!(attribute(cases[1], "name").as_deref(), Some("bad <&>"));
        let failures: Vec<&Element> = elements.iter().filter(|e| e.name == "failure").collect();
        assert_eq!(failures.len(), 2);
        assert_eq!(attribute(failures[0], "message").as_deref(), Some("flip 0.5 > 0.01, \"quoted\""));
        assert_eq!(attribute(failures[1], "type").as_deref(), Some("no-golden"));
        // Each failure sits inside the testcase that failed, and each testcase in the testsuite.
        let parent_name = |e: &Element| attribute(&elements[e.parent.unwrap()], "name");
        assert_eq!(failures.iter().map(|f| parent_name(f).unwrap()).collect::<Vec<_>>(), ["bad <&>", "new"]);
        assert!(cases.iter().all(|c| elements[c.parent.unwrap()].name == "testsuite"));
        assert_eq!(suite.parent, Some(0));
        // A failure says what made the image and which files were compared.
        let body = "flip 0.5 &gt; 0.01, &quot;quoted&quot;\nsettings: view shaded, max depth 5, 1 spp, 64x48\nscene: scenes/bad &lt;&amp;&gt;.toml\ngolden:";
        assert!(xml.contains(body), "{xml}");
    }

    #[test]
    fn each_student_is_a_testsuite() {
        let alice = [outcome("balls", Status::Passed, "flip 0 <= 0.01")];
        let bob = [outcome("balls", Status::NoImage, "no image"), outcome("room", Status::Mismatch, "flip 0.2 > 0.01")];
        let elements = parse(&junit_xml_suites("course", &[("alice", &alice), ("bob", &bob)]));
        let attribute = |e: &Element, key: &str| e.attributes.iter().find(|(k, _)| k == key).map(|(_, v)| v.clone());
        let totals: Vec<_> = ["tests", "failures"].iter().map(|k| attribute(&elements[0], k).unwrap()).collect();
        assert_eq!(totals, ["3", "2"]);
        let suites: Vec<_> =
            elements.iter().filter(|e| e.name == "testsuite").map(|e| (attribute(e, "name").unwrap(), attribute(e, "failures").unwrap())).collect();
        assert_eq!(suites, [("alice".to_string(), "0".to_string()), ("bob".into(), "2".into())]);
        let kinds: Vec<_> = elements.iter().filter(|e| e.name == "failure").map(|e| attribute(e, "type").unwrap()).collect();
        assert_eq!(kinds, ["no-image", "mismatch"]);
    }
}
