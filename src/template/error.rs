//! Template errors and located validation problems.

use std::fmt;

/// One problem found while validating a template, with where it is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TemplateProblem {
    /// The file (path, or `builtin:<name>` for a bundled template).
    pub file: String,
    /// Key path inside the file, e.g. `joint[3] (elbow).parent` or `ratios.human_arm`.
    pub path: String,
    /// 1-based line of the offending table or value, where known.
    pub line: Option<usize>,
    /// What is wrong and what to do, lowercase.
    pub message: String,
}

impl fmt::Display for TemplateProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{}: {}: {}", self.file, line, self.path, self.message),
            None => write!(f, "{}: {}: {}", self.file, self.path, self.message),
        }
    }
}

fn list(problems: &[TemplateProblem]) -> String {
    problems
        .iter()
        .map(|p| format!("\n  {p}"))
        .collect::<String>()
}

/// Errors of the template stage.
#[derive(Debug, thiserror::Error)]
pub enum TemplateError {
    /// The template file could not be read.
    #[error("cannot read template {path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The file is not valid TOML or does not have the template's shape.
    #[error("{file}:{}: invalid template: {message}", line.map_or("?".to_string(), |l| l.to_string()))]
    Parse {
        /// The file.
        file: String,
        /// 1-based line, where known.
        line: Option<usize>,
        /// The parser's message.
        message: String,
    },
    /// The file parsed but breaks template rules; every problem is listed.
    #[error("template {file} has {} problem(s); fix them and reload:{}", problems.len(), list(problems))]
    Invalid {
        /// The file.
        file: String,
        /// Every problem, in file order.
        problems: Vec<TemplateProblem>,
    },
    /// No bundled template has this name.
    #[error("unknown template {name:?}: use one of humanoid, quadruped, winged or a path to a .toml file")]
    UnknownTemplate {
        /// The name asked for.
        name: String,
    },
    /// No naming preset has this name.
    #[error("unknown naming preset {name:?}: use anatomical, mixamo, unity, makehuman or unreal")]
    UnknownPreset {
        /// The name asked for.
        name: String,
    },
    /// A bundled preset file is malformed (a build defect).
    #[error("naming preset {name} is malformed: {message}")]
    PresetFile {
        /// Preset name.
        name: String,
        /// What is wrong.
        message: String,
    },
}
