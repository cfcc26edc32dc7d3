//! WGSL sources from `shaders/`: a one-line include (`//!include common.wgsl`, a comment, so
//! each file stays plain WGSL text), naga parse + validate with errors mapped back to the
//! `file:line:col` they came from, and the checked source handed to wgpu.

use std::path::{Path, PathBuf};

use crate::diag::Diagnostic;

const INCLUDE: &str = "//!include ";

/// A shader expanded with its includes, and where each of its lines came from.
#[derive(Debug, Clone)]
pub struct ShaderSource {
    pub path: PathBuf,
    pub text: String,
    /// For line i (0-based) of `text`: the file and its 1-based line.
    line_map: Vec<(PathBuf, usize)>,
    /// Every file this source was built from (itself first), for hot reload.
    pub files: Vec<PathBuf>,
}

impl ShaderSource {
    /// Maps a 1-based line of the expanded text to (file, line).
    pub fn origin(&self, line: usize) -> (PathBuf, usize) {
        self.line_map
            .get(line.saturating_sub(1))
            .cloned()
            .unwrap_or_else(|| (self.path.clone(), line))
    }
}

/// Reads a shader and expands its includes (resolved beside it, one level, no cycles).
pub fn load(path: &Path) -> Result<ShaderSource, Diagnostic> {
    let text = read(path)?;
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut out = String::new();
    let mut line_map = Vec::new();
    let mut files = vec![path.to_path_buf()];
    for (i, line) in text.lines().enumerate() {
        if let Some(name) = line.trim_start().strip_prefix(INCLUDE) {
            let name = name.trim();
            // includes stay inside the shader folder
            if name.contains("..") || name.contains('/') || name.contains('\\') {
                return Err(Diagnostic::new(
                    path,
                    i + 1,
                    1,
                    format!("bad include {name:?}"),
                ));
            }
            let inc_path = dir.join(name);
            let inc = read(&inc_path).map_err(|d| {
                Diagnostic::new(path, i + 1, 1, format!("include {name:?}: {}", d.message))
            })?;
            for (j, l) in inc.lines().enumerate() {
                if l.trim_start().starts_with(INCLUDE) {
                    return Err(Diagnostic::new(
                        &inc_path,
                        j + 1,
                        1,
                        "nested includes are not supported",
                    ));
                }
                out.push_str(l);
                out.push('\n');
                line_map.push((inc_path.clone(), j + 1));
            }
            files.push(inc_path);
        } else {
            out.push_str(line);
            out.push('\n');
            line_map.push((path.to_path_buf(), i + 1));
        }
    }
    Ok(ShaderSource {
        path: path.to_path_buf(),
        text: out,
        line_map,
        files,
    })
}

/// Through the project's file source (disk, or the web player's bundle), like every project file.
fn read(path: &Path) -> Result<String, Diagnostic> {
    crate::project_files::read_to_string(path)
        .map_err(|e| Diagnostic::whole_file(path, format!("cannot read shader: {e}")))
}

/// Parses and validates with naga; the error names the original file, line and column, and its
/// message is naga's own rendering (with the source excerpt).
pub fn validate(src: &ShaderSource) -> Result<(naga::Module, naga::valid::ModuleInfo), Diagnostic> {
    let module = naga::front::wgsl::parse_str(&src.text).map_err(|e| {
        let (line, col) = e
            .location(&src.text)
            .map(|l| (l.line_number as usize, l.line_position as usize))
            .unwrap_or((0, 0));
        diag_at(
            src,
            line,
            col,
            e.emit_to_string_with_path(&src.text, &src.path.display().to_string()),
        )
    })?;
    let mut validator = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    );
    let info = validator.validate(&module).map_err(|e| {
        let (line, col) = e
            .location(&src.text)
            .map(|l| (l.line_number as usize, l.line_position as usize))
            .unwrap_or((0, 0));
        diag_at(
            src,
            line,
            col,
            e.emit_to_string_with_path(&src.text, &src.path.display().to_string()),
        )
    })?;
    Ok((module, info))
}

fn diag_at(src: &ShaderSource, line: usize, col: usize, message: String) -> Diagnostic {
    if line == 0 {
        return Diagnostic::whole_file(&src.path, message);
    }
    let (file, line) = src.origin(line);
    Diagnostic::new(file, line, col, remap_lines(src, message.trim_end()))
}

/// naga renders its excerpt with line numbers of the expanded text (includes pasted in):
/// rewrite `path:L:C` and the `L │` gutter to the lines of the file they came from.
fn remap_lines(src: &ShaderSource, message: &str) -> String {
    let path = format!("{}:", src.path.display());
    message
        .lines()
        .map(|l| {
            if let Some(at) = l.find(&path) {
                let rest = &l[at + path.len()..];
                let mut parts = rest.splitn(2, ':');
                if let (Some(Ok(n)), Some(tail)) =
                    (parts.next().map(str::parse::<usize>), parts.next())
                {
                    let (file, line) = src.origin(n);
                    return format!("{}{}:{line}:{tail}", &l[..at], file.display());
                }
            } else if let Some((num, tail)) = l.split_once(" │")
                && let Ok(n) = num.trim().parse::<usize>()
            {
                let (_, line) = src.origin(n);
                return format!("{:>width$} │{tail}", line, width = num.len());
            }
            l.to_string()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// A shader that naga parsed and validated: the expanded source, naga's module and what the
/// validator learnt (which globals each entry point uses).
pub struct Checked {
    pub src: ShaderSource,
    pub module: naga::Module,
    pub info: naga::valid::ModuleInfo,
}

impl Checked {
    /// A diagnostic at byte `offset` of the expanded text, in the file and line it came from.
    pub fn diag_at_offset(&self, offset: usize, message: impl Into<String>) -> Diagnostic {
        let text = &self.src.text[..offset.min(self.src.text.len())];
        let line = text.matches('\n').count() + 1;
        let col = text[text.rfind('\n').map_or(0, |i| i + 1)..]
            .chars()
            .count()
            + 1;
        let (file, line) = self.src.origin(line);
        Diagnostic::new(file, line, col, message)
    }
}

/// Load and validate; the expanded, checked source on success.
pub fn load_checked(path: &Path) -> Result<Checked, Diagnostic> {
    let src = load(path)?;
    let (module, info) = validate(&src)?;
    Ok(Checked { src, module, info })
}

/// For `lectern check`: the problems of one shader file. Include-only files (named `*common*`
/// or without an entry point) are checked through the shaders that include them.
pub fn check_file(path: &Path) -> Vec<Diagnostic> {
    match load(path) {
        Err(d) => vec![d],
        Ok(src) => {
            if !has_entry_point(&src.text) {
                return Vec::new();
            }
            validate(&src).err().into_iter().collect()
        }
    }
}

/// Whether a shader text declares an entry point (include-only files do not).
pub fn has_entry_point(text: &str) -> bool {
    ["@vertex", "@fragment", "@compute"]
        .iter()
        .any(|e| text.contains(e))
}

/// Every `.wgsl` file of a folder, sorted.
pub fn list(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "wgsl"))
        .collect();
    v.sort();
    v
}
