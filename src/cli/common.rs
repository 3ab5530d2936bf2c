//! Pieces shared by several subcommands.

use anyhow::Context;
use clap::Args;
use skelfit::mesh::Mesh;
use skelfit::voxel::{VoxelOptions, VoxelSize};
use skelfit::warning::{ranked, Warning, WarningRecord};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Voxel grid options shared by every command that voxelizes.
#[derive(Debug, Clone, Args)]
pub struct VoxelArgs {
    /// Voxel edge as a fraction of the longest bounding-box side (dissertation Table 5.2).
    #[arg(long, value_name = "F", default_value_t = 0.01, conflicts_with_all = ["voxel_length", "resolution"])]
    pub voxel_size: f64,
    /// Voxel edge in mesh units (instead of --voxel-size).
    #[arg(long, value_name = "L")]
    pub voxel_length: Option<f64>,
    /// Voxels along the longest bounding-box side (instead of --voxel-size).
    #[arg(long, value_name = "N")]
    pub resolution: Option<u32>,
    /// Refuse grids with more voxels than this.
    #[arg(long, value_name = "N", default_value_t = VoxelOptions::default().max_voxels)]
    pub max_voxels: usize,
    /// A grid sized by --voxel-size is refined once when the figure holds fewer interior
    /// voxels than this (thin limbs of long figures); 0 keeps it. --voxel-length and
    /// --resolution grids are kept as given.
    #[arg(long, value_name = "N", default_value_t = VoxelOptions::default().min_interior)]
    pub min_interior_voxels: usize,
}

impl VoxelArgs {
    /// Validated voxel options ([`VoxelOptions::validate`]), checked before any work.
    pub fn options(&self) -> anyhow::Result<VoxelOptions> {
        let size = match (self.voxel_length, self.resolution) {
            (Some(length), _) => VoxelSize::Absolute(length),
            (None, Some(0)) => anyhow::bail!("--resolution must be at least 1"),
            (None, Some(n)) => VoxelSize::Fraction(1.0 / n as f64),
            (None, None) => VoxelSize::Fraction(self.voxel_size),
        };
        let options = VoxelOptions {
            size,
            max_voxels: self.max_voxels,
            min_interior: match (self.voxel_length, self.resolution) {
                (None, None) => self.min_interior_voxels,
                _ => 0,
            },
            ..Default::default()
        };
        options
            .validate()
            .context("invalid --voxel-size, --voxel-length, --resolution or --max-voxels")?;
        Ok(options)
    }
}

/// Loads a mesh with the file name in the error context.
pub fn load_mesh(path: &Path) -> anyhow::Result<Mesh> {
    skelfit::mesh::load(path).with_context(|| format!("loading mesh {}", path.display()))
}

/// Loads a mesh and what the file held beyond it ([`skelfit::mesh::load_model`]: glTF and
/// OBJ models, written back by [`skelfit::export::model_glb_bytes`]).
pub fn load_model(path: &Path) -> anyhow::Result<(Mesh, Option<skelfit::mesh::SourceModel>)> {
    skelfit::mesh::load_model(path).with_context(|| format!("loading mesh {}", path.display()))
}

/// Prints what the output leaves out of the user's model; with `--bones` the output holds
/// the welded mesh instead of the model.
pub fn print_model_warnings(model: &skelfit::mesh::SourceModel, bones: bool) {
    if bones {
        warn(
            "with --bones the .glb holds the welded mesh (no UVs, materials or textures of the input)",
            "export",
            "notice",
        );
        return;
    }
    for w in &model.warnings {
        warn(&w.to_string(), "export", "notice");
    }
}

/// The frame of a written .glb, and what to tell the user about it.
#[derive(Debug, Clone)]
pub struct ChosenFrame {
    /// Mesh frame → file frame.
    pub frame: skelfit::export::OutputFrame,
    /// One line for the summary: the file's frame and units and where they came from.
    pub note: String,
    /// A warning when `--units auto` could not tell the units.
    pub warning: Option<String>,
    /// The mesh's units (`None` with `--keep-frame`).
    pub units: Option<skelfit::export::Units>,
}

impl ChosenFrame {
    /// The choice as JSON for `run` information.
    pub fn json(&self) -> serde_json::Value {
        let r = self.frame.rotation;
        serde_json::json!({
            "rotation": [r.x, r.y, r.z, r.w],
            "scale": self.frame.scale,
            "mesh_units": self.units.map(|u| u.symbol()),
        })
    }
}

/// The output frame of a .glb (`--keep-frame`, `--units`): glTF's +Y up, +Z forward, metres
/// from the figure's `up` and `forward` and the mesh's units (guessed from its height along
/// `up` with `auto`), or the mesh's own frame with `keep_frame`.
pub fn output_frame(
    keep_frame: bool,
    units: &str,
    mesh: &Mesh,
    up: glam::DVec3,
    forward: glam::DVec3,
) -> anyhow::Result<ChosenFrame> {
    use skelfit::export::{OutputFrame, Units};
    if keep_frame {
        return Ok(ChosenFrame {
            frame: OutputFrame::IDENTITY,
            note: "the mesh's own frame and units (--keep-frame)".into(),
            warning: None,
            units: None,
        });
    }
    let (low, high) = mesh
        .positions
        .iter()
        .map(|p| p.dot(up))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), d| {
            (l.min(d), h.max(d))
        });
    let height = (high - low).max(0.0);
    let (chosen, how, warning) = match units {
        "mm" => (Units::Millimetres, "given".to_string(), None),
        "cm" => (Units::Centimetres, "given".to_string(), None),
        "m" => (Units::Metres, "given".to_string(), None),
        "in" => (Units::Inches, "given".to_string(), None),
        "auto" => {
            let guess = Units::guess(height);
            let warning = (!guess.confident).then(|| {
                format!(
                    "the figure is {height:.4} units tall, outside the heights --units auto \
                     knows (0.3-3 m, 30-300 cm, 300-3000 mm); the .glb takes them as metres, \
                     pass --units mm|cm|m|in if they are not"
                )
            });
            (
                guess.units,
                format!("guessed from the height {height:.4} by --units auto"),
                warning,
            )
        }
        other => anyhow::bail!("--units {other}: expected mm, cm, m, in or auto"),
    };
    let frame = OutputFrame::new(up, forward, chosen.metres());
    let f = |v: glam::DVec3| format!("({:.3}, {:.3}, {:.3})", v.x, v.y, v.z);
    Ok(ChosenFrame {
        frame,
        note: format!(
            "glTF's +Y up, +Z forward, metres (mesh up {}, forward {}, units {} {how}; \
             --keep-frame keeps the mesh's)",
            f(up),
            f(forward),
            chosen.symbol()
        ),
        warning,
        units: Some(chosen),
    })
}

/// Milliseconds since `start`.
pub fn millis(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}

/// The output files of a command: every path checked before any work
/// ([`skelfit::output::check_outputs`]), the contents collected while working, and all written
/// together at the end ([`skelfit::output::write_all_atomic`]): either every output is written
/// or none is.
#[derive(Debug, Default)]
pub struct Outputs {
    files: Vec<(PathBuf, Vec<u8>)>,
}

impl Outputs {
    /// Checks `outputs` (folder exists and is writable, not a folder, not one of `inputs`, no
    /// two the same) before any work.
    pub fn check<'a>(
        outputs: impl IntoIterator<Item = &'a Path>,
        inputs: impl IntoIterator<Item = &'a Path>,
    ) -> anyhow::Result<Self> {
        let outputs: Vec<&Path> = outputs.into_iter().collect();
        let inputs: Vec<&Path> = inputs.into_iter().collect();
        match skelfit::output::check_outputs(&outputs, &inputs) {
            Err(e @ skelfit::output::OutputError::IsInput { .. }) => {
                Err(UsageError(e.to_string()).into())
            }
            other => Ok(other.map(|()| Self::default())?),
        }
    }

    /// Adds a file to write at the end.
    pub fn add(&mut self, path: &Path, bytes: impl Into<Vec<u8>>) {
        self.files.push((path.to_path_buf(), bytes.into()));
    }

    /// Adds a glTF file to write at the end: the GLB bytes as they are for `.glb`, as JSON
    /// with the data embedded for `.gltf` ([`MeshFormat`]).
    pub fn add_mesh(&mut self, path: &Path, glb: Vec<u8>) -> anyhow::Result<()> {
        let bytes = MeshFormat::of(path, "-o")?.encode(glb)?;
        self.add(path, bytes);
        Ok(())
    }

    /// Writes every file added, all-or-nothing.
    pub fn write(self) -> anyhow::Result<()> {
        let files: Vec<(&Path, &[u8])> = self
            .files
            .iter()
            .map(|(p, b)| (p.as_path(), b.as_slice()))
            .collect();
        skelfit::output::write_all_atomic(&files)?;
        Ok(())
    }
}

/// Creates an output folder (and its parents) and checks that files can be written in it,
/// before any work.
pub fn output_folder(dir: &Path) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    skelfit::output::check_outputs(&[&dir.join("skelfit-probe")], &[])
        .with_context(|| format!("checking that {} is writable", dir.display()))?;
    Ok(())
}

/// A mistake in what the user asked for (an output that is an input, an unknown output
/// extension): exit code 2, as for invalid command-line usage.
#[derive(Debug)]
pub struct UsageError(pub String);

impl std::fmt::Display for UsageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for UsageError {}

/// A batch that ran to its end but in which some models failed (`skelfit batch`): exit code
/// 3, so that scripts can tell it from an error that stopped the run (1).
#[derive(Debug)]
pub struct SomeFailed(pub String);

impl std::fmt::Display for SomeFailed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SomeFailed {}

/// How a glTF output is written, chosen by its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// `.glb`: binary glTF.
    Glb,
    /// `.gltf`: JSON glTF with the binary data embedded (base64 `data:` URI).
    Gltf,
}

impl MeshFormat {
    /// The format of an output mesh file named by `option` (`-o`): `.glb` or `.gltf`
    /// (case-insensitive); another extension is a [`UsageError`] naming the accepted ones.
    pub fn of(path: &Path, option: &str) -> anyhow::Result<Self> {
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match extension.as_deref() {
            Some("glb") => Ok(Self::Glb),
            Some("gltf") => Ok(Self::Gltf),
            _ => Err(UsageError(format!(
                "{option} {}: unknown output extension; skelfit writes .glb (binary glTF) or \
                 .gltf (glTF JSON with the data embedded)",
                path.display()
            ))
            .into()),
        }
    }

    /// The file's bytes from GLB bytes.
    pub fn encode(self, glb: Vec<u8>) -> anyhow::Result<Vec<u8>> {
        Ok(match self {
            Self::Glb => glb,
            Self::Gltf => skelfit::export::gltf_text_from_glb(&glb)?,
        })
    }
}

/// Checks a mesh output's extension (see [`MeshFormat::of`]).
pub fn require_mesh_output(path: &Path, option: &str) -> anyhow::Result<()> {
    MeshFormat::of(path, option).map(|_| ())
}

/// Writes a file atomically with its name in the error context.
pub fn write_file(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    skelfit::output::write_atomic(path, bytes)
        .with_context(|| format!("writing {}", path.display()))
}

/// `--up`: `auto` (found from the figure) or a direction.
pub fn parse_up(text: &str) -> anyhow::Result<skelfit::anatomy::Up> {
    use anyhow::Context;
    if text.eq_ignore_ascii_case("auto") {
        return Ok(skelfit::anatomy::Up::Auto);
    }
    let d = skelfit::anatomy::parse_direction(text)
        .map_err(anyhow::Error::msg)
        .context("--up")?;
    Ok(skelfit::anatomy::Up::Direction(d))
}

/// `--forward`: `auto` (guessed from head/tail or feet) or a direction.
pub fn parse_forward(text: &str) -> anyhow::Result<skelfit::anatomy::Forward> {
    use anyhow::Context;
    if text.eq_ignore_ascii_case("auto") {
        return Ok(skelfit::anatomy::Forward::Auto);
    }
    let d = skelfit::anatomy::parse_direction(text)
        .map_err(anyhow::Error::msg)
        .context("--forward")?;
    Ok(skelfit::anatomy::Forward::Direction(d))
}

/// A hint for labels that make no complete body plan (a humanoid's two legs, two arms and
/// head; a quadruped's four legs and head; a winged figure's two legs, two wings and head):
/// the commonest cause is a mesh whose up axis is not the one assumed (Z-up files from CAD
/// tools and scanners read as +Y up lie on their back).
pub fn orientation_hint(labels: &skelfit::anatomy::Labelling, up: glam::DVec3) -> Option<String> {
    use skelfit::anatomy::{FigureClass, Label};
    let count = |label| labels.find(label).len();
    let (legs, arms, wings, heads) = (
        count(Label::Leg),
        count(Label::Arm),
        count(Label::Wing),
        count(Label::Head),
    );
    let complete = heads == 1
        && match labels.figure {
            FigureClass::HumanLike => legs == 2 && arms == 2,
            FigureClass::AnimalLike => legs == 4 || (legs == 2 && wings == 2),
            FigureClass::Unknown => false,
        };
    (!complete).then(|| {
        format!(
            "the labels make no complete humanoid, quadruped or winged figure with up = ({:.3}, \
             {:.3}, {:.3}) ({legs} legs, {arms} arms, {wings} wings, {heads} heads); if the \
             mesh's up axis is another one, pass it with --up and a forward axis across it with \
             --forward (Z-up files from Blender, CAD tools and scanners: --up +Z --forward -Y)",
            up.x, up.y, up.z
        )
    })
}

/// Options every command takes (`global = true`): `--json`, `-q`, `-v`.
#[derive(Debug, Clone, Copy, Default, Args)]
pub struct GlobalArgs {
    /// Print the command's machine-readable result as JSON on stdout (the summary for people
    /// goes to stderr). Files are named by their own options (-o, --skeleton-json FILE, ...).
    /// `--print-json` is a deprecated alias, removed in the next release.
    #[arg(long, global = true, visible_alias = "print-json")]
    pub json: bool,
    /// Quiet: print errors only (no summary, warnings, hints or progress).
    #[arg(short, long, global = true, conflicts_with = "verbose")]
    pub quiet: bool,
    /// Verbose: print every warning on its own line instead of grouped by kind.
    #[arg(short, long, global = true)]
    pub verbose: bool,
}

/// The commands `skelfit --help` lists first, in this order; the rest follow alphabetically.
pub const MAIN_COMMANDS: [&str; 3] = ["rig", "skin", "check"];

/// The `display_order` of a subcommand in `skelfit --help`: the [`MAIN_COMMANDS`] first.
pub fn help_order(name: &str) -> usize {
    MAIN_COMMANDS
        .iter()
        .position(|main| *main == name)
        .unwrap_or(MAIN_COMMANDS.len())
}

static GLOBAL: std::sync::OnceLock<GlobalArgs> = std::sync::OnceLock::new();

/// Records the global options once, after parsing.
pub fn set_global(global: GlobalArgs) {
    let _ = GLOBAL.set(global);
}

/// The global options (all off until [`set_global`]).
pub fn global() -> GlobalArgs {
    GLOBAL.get().copied().unwrap_or_default()
}

/// Whether `--json` asks for the machine-readable result on stdout.
pub fn json_mode() -> bool {
    global().json
}

/// Whether `-q` asks for errors only.
pub fn quiet() -> bool {
    global().quiet
}

/// Prints a line of the summary for people: on stdout, on stderr with `--json` (stdout holds
/// the JSON), nowhere with `-q`.
macro_rules! say {
    ($($arg:tt)*) => {{
        let g = $crate::cli::common::global();
        if g.quiet {
        } else if g.json {
            eprintln!($($arg)*);
        } else {
            println!($($arg)*);
        }
    }};
}
pub(crate) use say;

/// Prints `value` as pretty JSON on stdout: a command's result under `--json`.
pub fn print_json<T: serde::Serialize + ?Sized>(value: &T) -> anyhow::Result<()> {
    println!("{}", serde_json::to_string_pretty(value)?);
    Ok(())
}

/// Prints a line for people on stderr (a hint, a missing part, a note) unless `-q`.
pub fn note(line: &str) {
    if !quiet() {
        eprintln!("{line}");
    }
}

/// Prints a warning that has no typed [`Warning`] (an export notice) unless `-q`:
/// `skelfit: warning: MESSAGE [STAGE, SEVERITY]`.
pub fn warn(message: &str, stage: &str, severity: &str) {
    note(&format!(
        "skelfit: warning: {message} [{stage}, {severity}]"
    ));
}

/// Prints `warnings` to stderr ranked for the reader ([`skelfit::warning::ranked`]: parts
/// missing first, then degraded, then notices; grouped by stage) and grouped by kind (see
/// [`warning_lines`]); every warning on its own line with `-v`, none with `-q`.
pub fn print_warnings(warnings: &[Warning]) {
    let records: Vec<WarningRecord> = ranked(warnings).into_iter().map(Warning::record).collect();
    print_ranked_records(&records);
}

/// Prints warning records (an evaluation's) to stderr, most severe first, as
/// [`print_warnings`] does.
pub fn print_warning_records(records: &[WarningRecord]) {
    let mut ranked: Vec<WarningRecord> = records.to_vec();
    ranked.sort_by_key(|r| std::cmp::Reverse(r.severity));
    print_ranked_records(&ranked);
}

fn print_ranked_records(records: &[WarningRecord]) {
    let g = global();
    if g.quiet {
        return;
    }
    for line in warning_lines(records, g.verbose) {
        eprintln!("{line}");
    }
}

/// The lines that report `records` (already ranked): with `verbose` one per warning; else
/// duplicates merged (`(x3)`) and warnings of the same stage and code on one line with their
/// count and the items they name, e.g. `skelfit: warning: refine: kept at the unrefined
/// position (6): pelvis, neck, elbow_L, ... [refine, degraded; -v lists each]`. Groups keep
/// the order of their first warning.
pub fn warning_lines(records: &[WarningRecord], verbose: bool) -> Vec<String> {
    let line = |r: &WarningRecord, times: usize| {
        let times = if times > 1 {
            format!(" (x{times})")
        } else {
            String::new()
        };
        format!(
            "skelfit: warning: {}{times} [{}, {}]",
            r.message, r.stage, r.severity
        )
    };
    if verbose {
        return records.iter().map(|r| line(r, 1)).collect();
    }
    // Groups by (stage, code) in order of first appearance; messages deduplicated with counts.
    let mut groups: Vec<(&WarningRecord, Vec<(&str, usize)>)> = Vec::new();
    for r in records {
        let group = match groups
            .iter_mut()
            .position(|(first, _)| first.stage == r.stage && first.code == r.code)
        {
            Some(i) => &mut groups[i].1,
            None => {
                groups.push((r, Vec::new()));
                &mut groups.last_mut().expect("just pushed").1
            }
        };
        match group.iter_mut().find(|(m, _)| *m == r.message) {
            Some((_, n)) => *n += 1,
            None => group.push((&r.message, 1)),
        }
    }
    groups
        .into_iter()
        .map(|(first, messages)| match messages.as_slice() {
            [(_, n)] => line(first, *n),
            _ => group_line(first, &messages),
        })
        .collect()
}

/// One line for several distinct warnings of one kind.
fn group_line(first: &WarningRecord, messages: &[(&str, usize)]) -> String {
    let total: usize = messages.iter().map(|(_, n)| n).sum();
    let tail = format!("[{}, {}; -v lists each]", first.stage, first.severity);
    // "SUBJECT: rest" after an optional "stage: " prefix: the subject is the item it names.
    let prefix = format!("{}: ", first.stage);
    let split: Option<Vec<(&str, &str)>> = messages
        .iter()
        .map(|(m, _)| {
            let m = m.strip_prefix(prefix.as_str()).unwrap_or(m);
            m.split_once(": ")
                .filter(|(subject, _)| subject.split_whitespace().count() <= 3)
        })
        .collect();
    let Some(split) = split else {
        return format!(
            "skelfit: warning: {}: {total} warnings of kind {}, e.g. {} {tail}",
            first.stage, first.code, first.message
        );
    };
    let mut subjects: Vec<&str> = Vec::new();
    for (subject, _) in &split {
        if !subjects.contains(subject) {
            subjects.push(subject);
        }
    }
    const SHOWN: usize = 8;
    let mut names = subjects
        .iter()
        .take(SHOWN)
        .copied()
        .collect::<Vec<_>>()
        .join(", ");
    if subjects.len() > SHOWN {
        names.push_str(&format!(" and {} more", subjects.len() - SHOWN));
    }
    let rest = split[0].1;
    if split.iter().all(|(_, r)| *r == rest) {
        format!(
            "skelfit: warning: {}: {rest} ({total}): {names} {tail}",
            first.stage
        )
    } else {
        format!(
            "skelfit: warning: {}: {} ({total}): {names}; e.g. {}: {rest} {tail}",
            first.stage,
            first.code.replace('_', " "),
            split[0].0
        )
    }
}
