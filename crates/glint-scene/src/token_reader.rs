//! What the NFF and Rayshade readers share: tokens that remember where they
//! stand, and the reading of a statement's operands, whose errors name the
//! file, line and column.

use std::path::Path;

use glam::Vec3;

use crate::shape::ShapeProblem;
use crate::{quoted, LoadError, Location, Shape};

/// A whitespace-separated word of a scene file.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Token<'a> {
    pub text: &'a str,
    /// Byte offset in the source.
    pub offset: usize,
    pub line: usize,
}

/// Where a parser stands in its file.
pub(crate) struct Cursor<'a> {
    pub source: &'a str,
    pub path: &'a Path,
    pub tokens: Vec<Token<'a>>,
    /// The index of the next token.
    pub pos: usize,
    /// The keyword being read, for messages about its operands.
    pub statement: Option<Token<'a>>,
}

impl<'a> Cursor<'a> {
    pub fn new(source: &'a str, path: &'a Path, tokens: Vec<Token<'a>>) -> Self {
        Self { source, path, tokens, pos: 0, statement: None }
    }
}

/// A parser that reads its file token by token. Each format keeps its own
/// state beside its [`Cursor`]; the readers of operands are shared.
pub(crate) trait TokenReader<'a> {
    fn cursor(&self) -> &Cursor<'a>;
    fn cursor_mut(&mut self) -> &mut Cursor<'a>;
    fn warnings(&mut self) -> &mut Vec<LoadError>;
    /// Adds an object of `shapes`, in the current material.
    fn push(&mut self, shapes: Vec<Shape>);

    /// What to say about `token`, which is not the number `what`.
    fn not_a_number(&self, token: &Token, what: &str) -> String {
        format!("expected a number ({what}) for {}, found {}", self.statement_name(), quoted(token.text))
    }

    fn location(&self, token: &Token) -> Location {
        let source = self.cursor().source;
        let line_start = source[..token.offset].rfind('\n').map_or(0, |i| i + 1);
        let column = source[line_start..token.offset].chars().count() + 1;
        Location { line: token.line, column: Some(column) }
    }

    fn error(&self, token: &Token, message: impl Into<String>) -> LoadError {
        LoadError::new(self.cursor().path, Some(self.location(token)), message)
    }

    fn warn(&mut self, token: &Token, message: impl Into<String>) {
        let warning = self.error(token, message);
        self.warnings().push(warning);
    }

    fn statement_name(&self) -> String {
        match &self.cursor().statement {
            Some(t) => format!("{} (line {})", quoted(t.text), t.line),
            None => "the file".into(),
        }
    }

    fn peek(&self) -> Option<Token<'a>> {
        self.cursor().tokens.get(self.cursor().pos).copied()
    }

    /// The next token, which must exist: `what` says what was expected.
    fn expect(&mut self, what: &str) -> Result<Token<'a>, LoadError> {
        match self.peek() {
            Some(t) => {
                self.cursor_mut().pos += 1;
                Ok(t)
            }
            None => {
                let at = self.cursor().statement.or_else(|| self.cursor().tokens.last().copied());
                let message = format!("unexpected end of file: {} needs {what}", self.statement_name());
                Err(match at {
                    Some(t) => self.error(&t, message),
                    None => LoadError::new(self.cursor().path, None, message),
                })
            }
        }
    }

    fn number(&mut self, what: &str) -> Result<f32, LoadError> {
        let t = self.expect(what)?;
        match t.text.parse::<f32>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(self.error(&t, format!("{what}: {} is not a finite number", quoted(t.text)))),
            Err(_) => Err(self.error(&t, self.not_a_number(&t, what))),
        }
    }

    fn non_negative(&mut self, what: &str) -> Result<f32, LoadError> {
        let at = self.peek();
        let v = self.number(what)?;
        match at {
            Some(t) if v < 0.0 => Err(self.error(&t, format!("{what} must not be negative, found {v}"))),
            _ => Ok(v),
        }
    }

    fn vec3(&mut self, what: &str) -> Result<Vec3, LoadError> {
        Ok(Vec3::new(
            self.number(&format!("{what} x"))?,
            self.number(&format!("{what} y"))?,
            self.number(&format!("{what} z"))?,
        ))
    }

    fn color(&mut self, what: &str) -> Result<Vec3, LoadError> {
        Ok(Vec3::new(
            self.non_negative(&format!("{what} red"))?,
            self.non_negative(&format!("{what} green"))?,
            self.non_negative(&format!("{what} blue"))?,
        ))
    }

    /// Adds the shape `keyword` describes, or applies the shared policy to what
    /// stops it being one: a degenerate shape is skipped with a warning, one
    /// beyond the range of f32 is an error.
    fn push_built(&mut self, keyword: &Token, built: Result<Shape, ShapeProblem>) -> Result<(), LoadError> {
        match built {
            Ok(shape) => {
                self.push(vec![shape]);
                Ok(())
            }
            Err(ShapeProblem::Degenerate(warning)) => {
                self.warn(keyword, warning);
                Ok(())
            }
            Err(ShapeProblem::Overflows) => Err(self.overflow(keyword)),
        }
    }

    /// Adds the polygon `keyword` describes, kept with a warning when it is
    /// not planar, under the policy of [`push_built`](Self::push_built).
    fn push_polygon(&mut self, keyword: &Token, vertices: Vec<Vec3>) -> Result<(), LoadError> {
        let built = Shape::polygon(vertices).map(|(shape, non_planar)| {
            if let Some(warning) = non_planar {
                self.warn(keyword, warning);
            }
            shape
        });
        self.push_built(keyword, built)
    }

    fn overflow(&self, keyword: &Token) -> LoadError {
        self.error(keyword, format!("the `{}` reaches beyond the range of 32-bit floats", keyword.text))
    }
}
