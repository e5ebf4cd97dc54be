//! Gradescope's autograder results, the `results.json` its harness reads
//! from `/autograder/results/` after each submission: the total `score`, an
//! `output` for the whole submission, and one entry in `tests` per case with
//! its `name`, `score`, `max_score`, `status` and `output`, and the case's
//! `visibility` where the manifest sets one
//! (<https://gradescope-autograders.readthedocs.io/en/latest/specs/>).

use serde_json::json;

use crate::grading::{GradedCase, Grades};
use crate::html::points_text;
use crate::runner::Summary;

/// `grades` are one student's outcomes of `cases`, in the same order.
pub fn results_json(suite_name: &str, cases: &[&GradedCase], grades: &Grades) -> String {
    let total = grades.total();
    let tests: Vec<serde_json::Value> = grades
        .outcomes
        .iter()
        .zip(cases)
        .map(|(outcome, case)| {
            let points = outcome.points.expect("a graded outcome has points");
            let mut test = json!({
                "name": outcome.name,
                "score": points.earned,
                "max_score": points.possible,
                "status": if outcome.status.failed() { "failed" } else { "passed" },
                "output": outcome.explanation(),
            });
            if let Some(visibility) = case.visibility {
                test["visibility"] = visibility.name().into();
            }
            test
        })
        .collect();
    let output = format!("{suite_name}: {}; {} points", Summary::of(&grades.outcomes), points_text(total));
    let results = json!({ "score": total.earned, "output": output, "tests": tests });
    serde_json::to_string_pretty(&results).expect("JSON values always serialise") + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::criteria::Criteria;
    use crate::grading::{Reference, Student};
    use crate::metrics::Metric;
    use crate::runner::{Outcome, Points, Status};
    use crate::scoring::Scoring;
    use crate::settings::Visibility;

    fn outcome(name: &str, status: Status, earned: f64, possible: f64) -> Outcome {
        Outcome {
            name: name.into(),
            file_stem: name.into(),
            files: vec![("submission", format!("ann/{name}.png").into()), ("reference scene", format!("{name}.toml").into())],
            settings: Some("view shaded, max depth 5, 1 spp, 48x36".into()),
            status,
            detail: format!("detail of {name}"),
            points: Some(Points { earned, possible }),
            images: None,
            diagnosis: None,
        }
    }

    fn case(name: &str, visibility: Option<Visibility>) -> GradedCase {
        GradedCase {
            name: name.into(),
            image: format!("{name}.png"),
            reference: Reference::Scene(format!("{name}.toml").into()),
            render: Default::default(),
            criteria: Criteria::for_metric(Metric::Flip),
            scoring: Scoring { points: 10.0, partial: Vec::new() },
            visibility,
        }
    }

    #[test]
    fn the_documented_fields_are_there() {
        let grades = Grades {
            student: Student { name: "ann".into(), dir: "ann".into(), report_folder: "ann".into() },
            outcomes: vec![outcome("balls", Status::Passed, 10.0, 10.0), outcome("room", Status::Mismatch, 2.5, 5.0)],
        };
        let (balls, room) = (case("balls", None), case("room", Some(Visibility::AfterDueDate)));
        let results: serde_json::Value = serde_json::from_str(&results_json("course", &[&balls, &room], &grades)).unwrap();
        assert_eq!(results["score"], 12.5);
        assert_eq!(results["output"], "course: 1 passed, 1 failed; 12.5/15 points");
        let tests = results["tests"].as_array().unwrap();
        assert_eq!(tests.len(), 2);
        assert_eq!((&tests[1]["name"], &tests[1]["score"], &tests[1]["max_score"], &tests[1]["status"]), (&json!("room"), &json!(2.5), &json!(5.0), &json!("failed")));
        assert_eq!(tests[0]["status"], "passed");
        // Gradescope's default unless the case sets its own.
        assert_eq!((tests[0].get("visibility"), &tests[1]["visibility"]), (None, &json!("after_due_date")));
        assert_eq!(
            tests[1]["output"],
            "detail of room\nsettings: view shaded, max depth 5, 1 spp, 48x36\nsubmission: ann/room.png\nreference scene: room.toml"
        );
    }
}
