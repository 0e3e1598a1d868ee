//! The `fairsub` command line: argument definitions and the subcommands, a thin front end over
//! the registry of schemes and the library.
//!
//! Each subcommand lives in its own module and returns [`crate::Result`], so every failure
//! reaches [`main`] as one error with a clear message (exit code 1); clap handles usage errors
//! (exit code 2). What a command prints goes through `say!`, so [`capture`] can collect it (a
//! test runs a command in-process and reads its report).

/// Writes one line of a command's report (standard output, or the [`capture`] buffer).
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::cli::say_line(format!($($arg)*))
    };
}

mod analyze;
pub mod api;
pub mod batch;
mod cad;
pub(crate) mod check;
mod compare;
mod demo;
mod eval;
mod info;
pub mod limits;
mod measure;
mod project;
mod reference;
mod render;
pub(crate) mod spec;
pub(crate) mod subdivide;
mod view;

pub use subdivide::Computed;

use crate::error::Result;
use crate::io::LoadedMesh;
use crate::schemes::options::ids;
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use std::cell::RefCell;
use std::path::PathBuf;
use std::process::ExitCode;

thread_local! {
    /// Where `say!` writes on this thread: `None` is standard output.
    static SINK: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Writes a line to this thread's sink.
pub(crate) fn say_line(line: String) {
    SINK.with(|s| match s.borrow_mut().as_mut() {
        Some(buf) => {
            buf.push_str(&line);
            buf.push('\n');
        }
        None => println!("{line}"),
    });
}

/// Writes `value` as pretty-printed JSON (one line break at the end) to this thread's sink.
pub(crate) fn say_json<T: serde::Serialize>(value: &T) {
    say!(
        "{}",
        serde_json::to_string_pretty(value).expect("serialisable")
    );
}

/// Writes a block of complete lines of ASCII or UTF-8 text (each ending in a newline) to this
/// thread's sink: one write for many lines (`fairsub eval`'s 10^6 points), no check of the
/// text on the way to standard output.
///
/// # Errors
/// [`crate::Error::Io`] when standard output fails (a closed pipe: `fairsub eval ... | head`),
/// [`crate::Error::InvalidOutput`] for text that is not UTF-8 while reports are collected.
pub(crate) fn say_bytes(text: &[u8]) -> crate::Result<()> {
    SINK.with(|s| match s.borrow_mut().as_mut() {
        Some(buf) => {
            let text = std::str::from_utf8(text)
                .map_err(|e| crate::Error::InvalidOutput(format!("report text: {e}")))?;
            buf.push_str(text);
            Ok(())
        }
        None => raw_stdout(text).map_err(|source| crate::Error::Io {
            path: "standard output".into(),
            source,
        }),
    })
}

/// Writes `text` to standard output past its line buffer (through a copy of its descriptor,
/// made on first use): blocks of whole lines need no buffering, and the line buffer searched
/// every block of `fairsub eval`'s 281 MB for its last newline.
#[cfg(unix)]
fn raw_stdout(text: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    thread_local! {
        static RAW: RefCell<Option<std::fs::File>> = RefCell::new({
            use std::os::fd::AsFd;
            // what was printed through the buffer goes first
            let _ = std::io::stdout().flush();
            std::io::stdout()
                .as_fd()
                .try_clone_to_owned()
                .ok()
                .map(std::fs::File::from)
        });
    }
    RAW.with(|raw| match raw.borrow_mut().as_mut() {
        Some(file) => file.write_all(text),
        None => std::io::stdout().lock().write_all(text),
    })
}

/// Writes `text` to standard output.
#[cfg(not(unix))]
fn raw_stdout(text: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    std::io::stdout().lock().write_all(text)
}

/// Runs `f` with the reports of commands collected instead of printed; returns them.
pub fn capture<T>(f: impl FnOnce() -> T) -> (T, String) {
    let old = SINK.with(|s| s.replace(Some(String::new())));
    let r = f();
    let out = SINK.with(|s| s.replace(old)).unwrap_or_default();
    (r, out)
}

/// The binary's entry point: parses the process's arguments and runs the command; exit code 0,
/// 1 with the error on stderr, or clap's 2 for usage errors.
pub fn main() -> ExitCode {
    let args = Cli::parse();
    match run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}

/// Runs a command line given as words (`["fairsub", "schemes"]`), as [`main`] would; usage
/// errors become [`crate::Error::InvalidArgument`] with clap's message.
pub fn run_words<I, T>(words: I) -> Result<()>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = Cli::try_parse_from(words)
        .map_err(|e| crate::error::Error::InvalidArgument(e.to_string()))?;
    run(cli)
}

/// The examples after `fairsub --help`.
fn examples() -> String {
    let cat = ids::CATMULL_CLARK;
    format!(
        "\
Examples:
  fairsub demo                                   run everything on the embedded default net
  fairsub info net.obj --json                    counts, valences, extraordinary elements
  fairsub subdivide net.obj --scheme {cat} --levels 3 -o fine.ply
  fairsub subdivide net.obj --scheme {cat} --rings 6 -o surface.bv
  fairsub subdivide gallery:cnet-5-saddle --scheme {cat} --rings 4 -o saddle.igs
  fairsub eval net.obj --scheme {cat} --at 0:0.5:0.25,3:0.1:0.9 --json
  fairsub schemes
  fairsub analyze --scheme {cat} --valence 5
  fairsub charmap --scheme {cat} --valence 5 -o chi5.svg
  fairsub check surface.bv
  fairsub check gallery:cnet-5-saddle --scheme {cat} --rings 6
  fairsub measure gallery:cube --scheme {cat} --json
  fairsub project gallery:cube --scheme {cat} --points points.txt

A NET argument is a file (.obj, .off, .ply) or gallery:NAME for a net of the built-in gallery
(`fairsub gallery --list`)."
    )
}

/// fairsub: subdivision surfaces of high shape quality.
#[derive(Debug, Parser)]
#[command(name = "fairsub", version, about, long_about = None, after_help = examples())]
pub struct Cli {
    /// Memory budget of the command (e.g. 4G, 512M; binary units). Jobs whose estimated size
    /// exceeds it are refused before anything is allocated. Default: half of the memory the
    /// process may use (physical memory, ulimit -v / -d, cgroup limit; see `fairsub --help`).
    #[arg(long, global = true, value_name = "SIZE")]
    max_memory: Option<String>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Counts, valences, extraordinary elements, boundaries and problems of a control net.
    Info {
        /// The control net (file or gallery:NAME).
        net: String,
        /// Also say what would be prepared for this scheme (`--prepare auto`): the steps, the
        /// needs they meet and the elements in the way, for patches and for net refinement.
        #[arg(long, short)]
        scheme: Option<String>,
        /// Print the report as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Refine a net (--levels) or write its exact surface as patches (--rings).
    #[command(after_help = "\
The output format follows the extension of -o (.obj .off .ply .bv .igs .iges) or --format.
Meshes (.obj/.off/.ply) get the refined net after --levels steps; with --rings they get a
watertight tessellation of the patch complex (--tess samples per patch edge). .bv and .igs get
the exact patch complex (default 6 rings); with --levels and no --rings, .bv gets the refined net
as a polyhedron.")]
    Subdivide(subdivide::Args),
    /// Evaluate the exact surface at parameters F:U:V of input faces (point, derivatives,
    /// normal, curvatures, patch).
    #[command(after_help = "\
Parameter domains: a quad face has (u, v) in [0,1]^2, corner 0 at (0,0), u toward corner 1, v
toward corner 3. An n-gon (n != 4, triangles included; Catmull-Clark, EG, QAS+, guided,
Doo-Sabin, DS^CC, PGS and its variants) has u in [0,n], v in [0,1]: sub-face
i = floor(u) is the quad at corner i (corner i, midpoint of the outgoing edge, centre, midpoint
of the incoming edge) at local (u - i, v), u toward the outgoing edge. A triangle (Loop) has
barycentric (u, v), u toward corner 1, v toward corner 2, u + v <= 1. Under the dual schemes
(Doo-Sabin, DS^CC, PGS) the quarter of a face at corner i (sub-face i of an n-gon) lies on
vertex i's patch (PGS after DS^CC: on the patches of its DS^CC-refined children; the mixed
bi-2 net: in a facet's rings at its corners); at a boundary vertex its patch's part over the
face (the face's boundary edge is the knot line through the boundary vertices, half a face
inside the boundary curve; at an extraordinary boundary vertex, its corner point's patches);
the quarters at boundary vertices under boundary mode none (no patch there) are not
evaluated; the TPS vertices of the mixed and polar bi-2 nets lay their rings in thirds of
their quarters, as TPS does. A pole's fan triangle
(polar and mixed bi-2 nets) has (u, v) in [0,1]^2: (0,0) at the corner after the pole, (1,0) at
the next, v = 1 the pole (u around it, v inward); an n-gon cap turned into a pole has u in
[0,n], v in [0,1], sub-face i = floor(u) its fan triangle at edge i -> i+1. EG, QAS+ (all
variants) and guided bi-5/bi-6 parametrise the faces around a capped vertex by their rings'
chart: ring k of the cap
covers the band between 2^-k and 2^-(k-1) of the face's square at the vertex, the cap the
square inside the last ring. TPS (ternary) lays a vertex's patch on the quarters of its faces
as the dual schemes do; ring k of an extraordinary vertex covers the band between 3^-k and
3^-(k-1) of the quarter at the vertex (in its halved coordinates), the cap the square inside
the last ring. Without --rings the
scheme's limit surface is evaluated (as many rings as each point needs, the limit point at an
extraordinary vertex); with --rings K the complex `subdivide --rings K` writes.")]
    Eval(eval::Args),
    /// Area, enclosed volume, centroids and inertia tensors of the exact surface, integrated
    /// exactly from its Bezier patches.
    Measure(measure::MeasureArgs),
    /// The closest points of the exact surface to points in space: input face, parameters (as
    /// `eval` takes them), point, distance and normal.
    Project(project::ProjectArgs),
    /// Draw highlight lines, reflection lines, isophotes, curvature or provenance as a PNG.
    Render(render::RenderArgs),
    /// A labelled PNG grid of schemes x modes with one camera, light set and curvature range.
    Compare(render::CompareArgs),
    /// List the schemes with their properties and supported valences.
    Schemes {
        /// Print the list as JSON.
        #[arg(long)]
        json: bool,
        /// Print the catalogue as a Markdown page (the guide's reference/schemes.md).
        #[arg(long, conflicts_with = "json")]
        markdown: bool,
    },
    /// Run the main job on the embedded default net and write the results into a folder.
    Demo {
        /// Folder for the results (created if missing).
        #[arg(long, short, default_value = ".")]
        out: PathBuf,
    },
    /// Spectrum, Fourier blocks, limit and tangent stencils and characteristic-map certificate of a
    /// scheme at one valence.
    Analyze(analyze::AnalyzeArgs),
    /// Write a scheme's characteristic ring (and its lambda-scaled copy) with its injectivity
    /// certificate.
    Charmap(analyze::CharmapArgs),
    /// Continuity report (C0/C1/C2/G1 defects per kind of join) and per-ring curvature ranges of a
    /// BezierView file or of a net's surface under a scheme.
    Check(check::CheckArgs),
    /// Interactive viewer in the browser: a local page (127.0.0.1) with highlight lines,
    /// curvature, overlays and scheme menu.
    View(view::ViewArgs),
    /// Run the jobs of a manifest (JSON Lines or CSV: nets, schemes, outputs, metrics) in
    /// parallel worker processes, with a result row per job in DIR/results.jsonl; a re-run
    /// skips what is done. --max-memory is per job.
    Batch(batch::Args),
    /// A worker process of `fairsub batch` (tasks on standard input, outcomes on standard
    /// output).
    #[command(hide = true)]
    BatchWorker,
    /// Print this command-line reference as a Markdown page (the guide's reference/cli.md).
    #[command(hide = true)]
    HelpMarkdown,
    /// Write the built-in gallery of control nets as OBJ files (or list their names).
    Gallery {
        /// Folder to write into.
        #[arg(long, short, required_unless_present = "list")]
        out: Option<PathBuf>,
        /// Only list the names.
        #[arg(long)]
        list: bool,
    },
}

/// Runs a parsed command line (within its memory budget, see [`Cli`]'s `--max-memory`).
pub fn run(cli: Cli) -> Result<()> {
    crate::linalg::deterministic();
    let budget = cli
        .max_memory
        .as_deref()
        .map(limits::parse_memory)
        .transpose()?;
    limits::with_budget(budget, || run_command(cli.command))
}

fn run_command(command: Command) -> Result<()> {
    match command {
        Command::Info { net, scheme, json } => info::run(&net, scheme.as_deref(), json),
        Command::Subdivide(args) => subdivide::run(args),
        Command::Eval(args) => eval::run(args),
        Command::Measure(args) => measure::run(args),
        Command::Project(args) => project::run(args),
        Command::Render(args) => render::run_render(args),
        Command::Compare(args) => render::run_compare(args),
        Command::Schemes { json, markdown } => schemes(json, markdown),
        Command::Demo { out } => demo::run(&out),
        Command::Analyze(a) => analyze::analyze(a),
        Command::Charmap(a) => analyze::charmap(a),
        Command::Check(a) => check::check(a),
        Command::View(a) => view::run(a),
        Command::Batch(a) => batch::run(a),
        Command::BatchWorker => batch::serve(std::io::stdin().lock(), std::io::stdout().lock()),
        Command::Gallery { out, list } => gallery(out, list),
        Command::HelpMarkdown => {
            use clap::CommandFactory;
            say!("{}", reference::cli_markdown(Cli::command()));
            Ok(())
        }
    }
}

/// Loads a net from a file or from the gallery (`gallery:NAME`); prints its warnings.
pub fn load_net(arg: &str) -> Result<LoadedMesh> {
    load_net_as(arg, false)
}

/// [`load_net`], tolerantly with `tolerant` (see [`crate::io::read_mesh_as`]).
pub fn load_net_as(arg: &str, tolerant: bool) -> Result<LoadedMesh> {
    let loaded = if let Some(name) = arg.strip_prefix("gallery:") {
        let all = crate::gallery::all();
        match all.into_iter().find(|(n, _)| n == name) {
            Some((_, mesh)) => LoadedMesh {
                mesh,
                warnings: Vec::new(),
            },
            None => {
                return Err(crate::Error::InvalidArgument(format!(
                    "no gallery net named '{name}' (see `fairsub gallery --list`)"
                )));
            }
        }
    } else {
        crate::io::read_mesh_as(std::path::Path::new(arg), tolerant)?
    };
    for w in &loaded.warnings {
        eprintln!("warning: {arg}: {w}");
    }
    Ok(loaded)
}

/// A progress bar over `len` steps on stderr; invisible when stderr is not a terminal.
pub fn progress_bar(len: u64, what: &str) -> ProgressBar {
    let pb = ProgressBar::new(len);
    if let Ok(style) = ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} ({elapsed})") {
        pb.set_style(style.progress_chars("=> "));
    }
    pb.set_message(what.to_string());
    pb
}

/// Valences the catalogue asks a scheme about: a range that reaches the end is shown as
/// "and above" (the schemes answer alike for every valence past their last construction).
const CATALOGUE_VALENCES: std::ops::RangeInclusive<usize> = 3..=64;

/// Consecutive valences with rules of one origin.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RulesRange {
    /// First valence.
    pub from: usize,
    /// Last valence (`None`: and every valence above).
    pub to: Option<usize>,
    /// Where the rules come from.
    pub origin: crate::schemes::descriptor::RulesOrigin,
    /// The rules at the first valence of the range, in words.
    pub rules: String,
}

/// The rules of a scheme by valence ranges, if its rules differ by valence.
fn rules_ranges(spec: &crate::schemes::Spec) -> Option<Vec<RulesRange>> {
    let d = crate::schemes::registry().descriptor(spec.id);
    let mut out: Vec<RulesRange> = Vec::new();
    for n in CATALOGUE_VALENCES {
        let v = d.valence_rules(spec, n)?;
        match out.last_mut() {
            Some(r) if r.origin == v.origin && r.to == Some(n - 1) => r.to = Some(n),
            _ => out.push(RulesRange {
                from: n,
                to: Some(n),
                origin: v.origin,
                rules: v.rules,
            }),
        }
    }
    if let Some(last) = out.last_mut()
        && last.to == Some(*CATALOGUE_VALENCES.end())
    {
        last.to = None;
    }
    Some(out)
}

/// A catalogue row (`fairsub schemes`): the scheme's catalogue text and its rules by valence.
#[derive(Debug, Clone, serde::Serialize)]
pub struct CatalogueRow {
    /// Name, family, input, patches, smoothness, status.
    #[serde(flatten)]
    pub info: crate::schemes::SchemeInfo,
    /// Rules by valence (default options), for schemes whose rules differ by valence.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rules_by_valence: Option<Vec<RulesRange>>,
    /// The same with `--rules derived`, where that changes them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rules_by_valence_derived: Option<Vec<RulesRange>>,
}

/// `3 printed, 4 regular, 6..16 derived, 17+ fallback (...)`.
fn ranges_words(rs: &[RulesRange]) -> String {
    use crate::schemes::descriptor::RulesOrigin;
    rs.iter()
        .map(|r| {
            let at = match r.to {
                None => format!("{}+", r.from),
                Some(t) if t == r.from => t.to_string(),
                Some(t) => format!("{}..{t}", r.from),
            };
            let what = match r.origin {
                RulesOrigin::Printed => "printed".to_string(),
                RulesOrigin::Derived => "derived (fairsub's reconstruction)".to_string(),
                RulesOrigin::Regular => "regular".to_string(),
                RulesOrigin::Borrowed | RulesOrigin::Fallback => r.rules.clone(),
            };
            format!("{at} {what}")
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The catalogue rows of every scheme, in the registry's order.
pub(crate) fn catalogue() -> Vec<CatalogueRow> {
    let reg = crate::schemes::registry();
    crate::schemes::catalog()
        .into_iter()
        .zip(reg.entries())
        .map(|(info, e)| {
            let plain = crate::schemes::Spec::new(e.id);
            let mut derived = plain.clone();
            derived.params.rules = crate::schemes::descriptor::RulesChoice::Derived;
            let a = rules_ranges(&plain);
            let b = rules_ranges(&derived);
            let changed = match (&a, &b) {
                (Some(x), Some(y)) => ranges_words(x) != ranges_words(y),
                _ => false,
            };
            CatalogueRow {
                info,
                rules_by_valence: a,
                rules_by_valence_derived: b.filter(|_| changed),
            }
        })
        .collect()
}

fn schemes(json: bool, markdown: bool) -> Result<()> {
    let rows = catalogue();
    if markdown {
        let entries = crate::schemes::registry().entries();
        say!("{}", reference::schemes_markdown(&rows, entries));
        return Ok(());
    }
    if json {
        say_json(&rows);
        return Ok(());
    }
    for row in rows {
        let s = &row.info;
        say!("{} [{}]", s.name, s.status);
        say!("  family:     {}", s.family);
        say!("  input:      {}", s.input);
        say!("  patches:    {}", s.patches);
        say!("  smoothness: {}", s.smoothness);
        say!("  valences:   {}", s.valences);
        if let Some(r) = &row.rules_by_valence {
            say!("  rules:      {}", ranges_words(r));
        }
        if let Some(r) = &row.rules_by_valence_derived {
            say!("  --rules derived: {}", ranges_words(r));
        }
        say!(
            "  commands:   {}{}",
            if s.refine { "subdivide --levels " } else { "" },
            if s.rings { "subdivide --rings" } else { "" }
        );
    }
    Ok(())
}

fn gallery(out: Option<PathBuf>, list: bool) -> Result<()> {
    let all = crate::gallery::all();
    if list {
        for (name, m) in &all {
            say!(
                "{name:24} {:4} vertices {:4} faces",
                m.num_vertices(),
                m.num_faces()
            );
        }
        return Ok(());
    }
    let dir = out.expect("clap requires --out without --list");
    std::fs::create_dir_all(&dir).map_err(|source| crate::Error::Io {
        path: dir.clone(),
        source,
    })?;
    for (name, m) in &all {
        let path = dir.join(format!("{name}.obj"));
        crate::io::write_mesh(&path, m, crate::io::MeshFormat::Obj)?;
    }
    say!("wrote {} nets to {}", all.len(), dir.display());
    Ok(())
}
