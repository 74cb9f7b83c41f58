//! The error-against-run-time report: every numerical method of the crate, measured in this
//! run, written as Markdown with SVG plots, plus a stability table of the stiff and extreme
//! cases the crate claims to handle.
//!
//! `cargo run --release --example report -- [DIR] [--quick] [--only SECTION]` writes
//! `DIR/report.md` (default `target/report`) and its plots, and prints the Markdown. `--quick`
//! runs fewer repetitions (for CI in a debug build; its timings mean little); `--only` runs one
//! section into `DIR/report_SECTION.md` (`spectrum`, `wind`, `freefall`, `presets`, `cloth`,
//! `aero`, `particle_cloth`, `measurements`, `costs`, `stability`).

mod aero;
mod cloth;
mod costs;
mod freefall;
mod measurements;
mod plot;
mod presets;
mod spectrum;
mod stability;
mod wind;

use std::fmt::Write as _;
use std::path::PathBuf;

use plot::Plot;

/// A section of the report: its name for `--only`, and what writes it.
type Section = (&'static str, fn(&mut Report));

/// The report being written.
pub struct Report {
    dir: PathBuf,
    markdown: String,
    /// Fewer repetitions, for a smoke run.
    pub quick: bool,
}

impl Report {
    /// A heading and a paragraph.
    pub fn section(&mut self, title: &str, text: &str) {
        let _ = write!(self.markdown, "## {title}\n\n");
        if !text.is_empty() {
            let _ = write!(self.markdown, "{text}\n\n");
        }
    }

    /// A paragraph.
    pub fn markdown_line(&mut self, text: &str) {
        let _ = write!(self.markdown, "{text}\n\n");
    }

    /// A Markdown table.
    pub fn table(&mut self, header: &[&str], rows: &[Vec<String>]) {
        let line = |cells: &[String]| format!("| {} |\n", cells.join(" | "));
        let head: Vec<String> = header.iter().map(|s| s.to_string()).collect();
        self.markdown += &line(&head);
        self.markdown += &line(&vec!["---".to_string(); header.len()]);
        for row in rows {
            self.markdown += &line(row);
        }
        self.markdown += "\n";
    }

    /// Draws `plot` into `DIR/name.svg` and links it.
    pub fn figure(&mut self, name: &str, plot: &Plot) {
        let file = format!("{name}.svg");
        match plot::draw(&self.dir.join(&file), plot) {
            Ok(()) => {
                let _ = write!(self.markdown, "![{}]({file})\n\n", plot.title);
            }
            Err(e) => eprintln!("plot {file}: {e}"),
        }
    }
}

/// `x` in scientific notation, or what went wrong with it.
pub fn sci(x: f64) -> String {
    if x.is_nan() {
        "NaN".into()
    } else if x.is_infinite() {
        "inf".into()
    } else {
        format!("{x:.2e}")
    }
}

fn main() {
    let mut dir = PathBuf::from("target/report");
    let mut quick = false;
    let mut only = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--quick" => quick = true,
            "--only" => {
                only = args.next();
                if only.is_none() {
                    eprintln!("--only needs a section name");
                    std::process::exit(2);
                }
            }
            other => dir = other.into(),
        }
    }
    std::fs::create_dir_all(&dir).expect("cannot create the report folder");
    let mut report = Report {
        dir: dir.clone(),
        markdown: String::new(),
        quick,
    };
    let build = if cfg!(debug_assertions) {
        "debug"
    } else {
        "release"
    };
    let _ = write!(
        report.markdown,
        "# bevy_windfall: error against run time\n\nMeasured in one run of `report` ({build} \
         build, {}, {} threads available). Every number and plot below comes from this run; \
         each time is the best of three batches.\n\n",
        cpu_name(),
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );
    let sections: [Section; 10] = [
        ("spectrum", spectrum::report),
        ("wind", wind::report),
        ("freefall", freefall::report),
        ("presets", presets::report),
        ("cloth", cloth::report),
        ("aero", aero::report),
        ("particle_cloth", aero::particle_cloth),
        ("measurements", measurements::report),
        ("costs", costs::report),
        ("stability", stability::report),
    ];
    if let Some(only) = &only
        && !sections.iter().any(|(name, _)| name == only)
    {
        let names: Vec<&str> = sections.iter().map(|(name, _)| *name).collect();
        eprintln!("no section {only:?}; the sections: {}", names.join(", "));
        std::process::exit(2);
    }
    for (name, section) in sections {
        if only.as_deref().is_none_or(|o| o == name) {
            section(&mut report);
        }
    }
    // One section goes beside the whole report, never over it.
    let path = dir.join(match &only {
        Some(name) => format!("report_{name}.md"),
        None => "report.md".into(),
    });
    std::fs::write(&path, &report.markdown).expect("cannot write report.md");
    println!("{}", report.markdown);
    eprintln!("report written to {}", path.display());
}

/// Wall time of one call of `f`, s: the mean over `repeats` calls (at least one), the best of
/// three such batches, so that a burst of other work on the machine does not count.
pub fn seconds_per(repeats: usize, mut f: impl FnMut()) -> f64 {
    let repeats = repeats.max(1);
    (0..3)
        .map(|_| {
            let start = std::time::Instant::now();
            for _ in 0..repeats {
                f();
            }
            start.elapsed().as_secs_f64() / repeats as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// The processor's name, where the system tells it.
fn cpu_name() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            let line = info.lines().find(|l| l.starts_with("model name"))?;
            Some(line.split_once(':')?.1.trim().to_string())
        })
        .unwrap_or_else(|| "unknown processor".into())
}
